// H.264 MP4 through libavcodec (libx264) and libavformat; RGBA -> yuv420p BT.709 with swscale
#include "rootsim/video_writer.hpp"
#include "rootsim/content_hash.hpp"
#include "rootsim/signature.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/error.h>
#include <libavutil/imgutils.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <system_error>

namespace rootsim {

namespace {

std::string avErr(int code) {
  char buf[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, buf, sizeof buf);
  return std::string(buf) + " (" + std::to_string(code) + ")";
}

// throw naming the call when a libav call returned a negative code
void check(int code, const std::string& call) {
  if (code < 0) throw RenderError("video: " + call + ": " + avErr(code));
}

// x264 hands over Annex B packets (start codes), which the MP4 muxer stores as NAL units with a 4-byte
// length each (FFmpeg's ff_avc_parse_nal_units): hashed as stored, so that the packets read back hash
// the same. A NAL starts after 00 00 01 (leading zeros skipped) and ends where the next start code, with
// one zero byte before it, begins.
void hashAsStored(Sha256& h, const std::uint8_t* p, std::size_t n) {
  auto startCode = [&](std::size_t from) {
    for (std::size_t i = from; i + 2 < n; ++i)
      if (p[i] == 0 && p[i + 1] == 0 && p[i + 2] == 1) return i;
    return n;
  };
  std::size_t at = startCode(0);
  if (at == n) {  // not Annex B: stored as it is
    h.update(p, n);
    return;
  }
  while (at < n) {
    std::size_t start = at;
    while (start < n && p[start] == 0) ++start;
    if (start >= n) break;
    if (++start >= n) break;  // past the 01: nothing after it
    std::size_t end = startCode(start);
    if (end < n && end > start && p[end - 1] == 0) --end;
    const auto len = static_cast<std::uint32_t>(end - start);
    const std::uint8_t be[4] = {static_cast<std::uint8_t>(len >> 24), static_cast<std::uint8_t>(len >> 16),
                                static_cast<std::uint8_t>(len >> 8), static_cast<std::uint8_t>(len)};
    h.update(be, 4);
    h.update(p + start, len);
    at = end;
  }
}

}  // namespace

std::string whyNotSignedMovie(const std::string& path) {
  AVFormatContext* in = nullptr;
  // a user's file is expected here: libavformat's complaints about it are not for the terminal
  const int level = av_log_get_level();
  av_log_set_level(AV_LOG_QUIET);
  const int opened = avformat_open_input(&in, path.c_str(), nullptr, nullptr);
  av_log_set_level(level);
  if (opened < 0) return "it does not open as a movie";
  struct Close {
    AVFormatContext** f;
    ~Close() { avformat_close_input(f); }
  } close{&in};
  const std::string format = in->iformat && in->iformat->name ? in->iformat->name : "";
  if (format.find("mp4") == std::string::npos) return "not an MP4 file (" + (format.empty() ? "unknown" : format) + ")";
  const AVDictionaryEntry* c = av_dict_get(in->metadata, "comment", nullptr, 0);
  const std::string comment = c && c->value ? c->value : "";
  if (comment.rfind(std::string(kOutputSignature) + " ", 0) != 0) return "its comment tag is not rootsim's";
  const auto at = comment.find(" sha256:");
  if (at == std::string::npos) return "";
  Sha256 h;
  AVPacket* pkt = av_packet_alloc();
  if (!pkt) return "cannot read its packets";
  int r = 0;
  while ((r = av_read_frame(in, pkt)) >= 0) {
    h.update(pkt->data, static_cast<std::size_t>(pkt->size));
    av_packet_unref(pkt);
  }
  av_packet_free(&pkt);
  if (r != AVERROR_EOF) return "its packets cannot be read: " + avErr(r);
  return h.hex() == comment.substr(at + 8, 64) ? "" : "changed since rootsim wrote it";
}

struct VideoWriter::Impl {
  std::string path, partial;
  int width = 0, height = 0;
  VideoOptions opt;
  AVFormatContext* fmt = nullptr;
  AVCodecContext* enc = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* pkt = nullptr;
  SwsContext* sws = nullptr;
  bool headerWritten = false, finished = false, ioOpen = false;
  int frames = 0;
  Sha256 packets;  // the hash of every packet's data, in the order written: the signature's sha256

  Impl(const std::string& p, int w, int h, const VideoOptions& o)
      : path(p), partial(p + ".partial"), width(w), height(h), opt(o) {
    if (w <= 0 || h <= 0 || w % 2 != 0 || h % 2 != 0)
      throw RenderError("video " + path + ": frame size " + std::to_string(w) + "x" + std::to_string(h) +
                        " must be positive and even (H.264 yuv420p halves the colour resolution)");
    if (o.fps < 1 || o.fps > 1000)
      throw RenderError("video " + path + ": fps must be in 1..1000 (got " + std::to_string(o.fps) + ")");
    if (o.crf < 0 || o.crf > 51)
      throw RenderError("video " + path + ": crf must be in 0..51 (got " + std::to_string(o.crf) + ")");
    // x264 prints INFO statistics to stderr otherwise (docs/rendering.md, Pitfalls)
    static std::once_flag quiet;
    std::call_once(quiet, [] { av_log_set_level(AV_LOG_ERROR); });
    try {
      open();
    } catch (...) {
      release();
      std::remove(partial.c_str());
      throw;
    }
  }

  void open() {
    // the muxer is named: ".partial" says nothing about the format
    check(avformat_alloc_output_context2(&fmt, nullptr, "mp4", partial.c_str()),
          "avformat_alloc_output_context2(mp4)");
    const AVCodec* codec = avcodec_find_encoder(AV_CODEC_ID_H264);
    if (!codec) throw RenderError("video: avcodec_find_encoder(H.264) found no encoder (libx264 missing?)");
    stream = avformat_new_stream(fmt, nullptr);
    if (!stream) throw RenderError("video: avformat_new_stream failed");
    enc = avcodec_alloc_context3(codec);
    if (!enc) throw RenderError("video: avcodec_alloc_context3 failed");
    enc->width = width;
    enc->height = height;
    enc->pix_fmt = AV_PIX_FMT_YUV420P;
    enc->time_base = AVRational{1, opt.fps};
    enc->framerate = AVRational{opt.fps, 1};
    enc->gop_size = 10 * opt.fps;
    // BT.709, limited range, tagged in the stream so players convert back with the same matrix
    enc->color_primaries = AVCOL_PRI_BT709;
    enc->color_trc = AVCOL_TRC_BT709;
    enc->colorspace = AVCOL_SPC_BT709;
    enc->color_range = AVCOL_RANGE_MPEG;
    if (fmt->oformat->flags & AVFMT_GLOBALHEADER) enc->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    check(av_opt_set(enc->priv_data, "preset", opt.preset.c_str(), 0), "av_opt_set(preset=" + opt.preset + ")");
    check(av_opt_set(enc->priv_data, "crf", std::to_string(opt.crf).c_str(), 0),
          "av_opt_set(crf=" + std::to_string(opt.crf) + ")");
    check(avcodec_open2(enc, codec, nullptr), std::string("avcodec_open2(") + codec->name + ")");
    check(avcodec_parameters_from_context(stream->codecpar, enc), "avcodec_parameters_from_context");
    stream->time_base = enc->time_base;
    stream->avg_frame_rate = enc->framerate;

    check(avio_open(&fmt->pb, partial.c_str(), AVIO_FLAG_WRITE), "avio_open(" + partial + ")");
    ioOpen = true;
    check(avformat_write_header(fmt, nullptr), "avformat_write_header(" + partial + ")");
    headerWritten = true;

    frame = av_frame_alloc();
    pkt = av_packet_alloc();
    if (!frame || !pkt) throw RenderError("video: av_frame_alloc/av_packet_alloc failed");
    frame->format = AV_PIX_FMT_YUV420P;
    frame->width = width;
    frame->height = height;
    frame->color_primaries = AVCOL_PRI_BT709;
    frame->color_trc = AVCOL_TRC_BT709;
    frame->colorspace = AVCOL_SPC_BT709;
    frame->color_range = AVCOL_RANGE_MPEG;
    check(av_frame_get_buffer(frame, 0), "av_frame_get_buffer");

    sws = sws_getContext(width, height, AV_PIX_FMT_RGBA, width, height, AV_PIX_FMT_YUV420P,
                         SWS_BILINEAR | SWS_ACCURATE_RND, nullptr, nullptr, nullptr);
    if (!sws) throw RenderError("video: sws_getContext(RGBA -> yuv420p) failed");
    // swscale defaults to BT.601: full-range RGB in, BT.709 limited-range YUV out
    const int* bt709 = sws_getCoefficients(SWS_CS_ITU709);
    check(sws_setColorspaceDetails(sws, bt709, 1, bt709, 0, 0, 1 << 16, 1 << 16),
          "sws_setColorspaceDetails(BT.709)");
  }

  // send one frame (or nullptr to flush) and write every packet the encoder returns
  void encode(AVFrame* f) {
    check(avcodec_send_frame(enc, f), "avcodec_send_frame");
    for (;;) {
      const int r = avcodec_receive_packet(enc, pkt);
      if (r == AVERROR(EAGAIN) || r == AVERROR_EOF) return;
      check(r, "avcodec_receive_packet");
      // libx264 in FFmpeg 5.1 leaves duration 0: the MP4 would come out one frame short
      if (pkt->duration <= 0) pkt->duration = 1;
      av_packet_rescale_ts(pkt, enc->time_base, stream->time_base);
      pkt->stream_index = stream->index;
      hashAsStored(packets, pkt->data, static_cast<std::size_t>(pkt->size));
      check(av_interleaved_write_frame(fmt, pkt), "av_interleaved_write_frame(" + partial + ")");
    }
  }

  void add(const Image& img) {
    if (finished) throw RenderError("video " + path + ": add() after finish()");
    if (img.width != width || img.height != height)
      throw RenderError("video " + path + ": frame " + std::to_string(frames) + " is " + std::to_string(img.width) +
                        "x" + std::to_string(img.height) + ", the movie is " + std::to_string(width) + "x" +
                        std::to_string(height));
    check(av_frame_make_writable(frame), "av_frame_make_writable");
    const std::uint8_t* src[1] = {img.rgba.data()};
    const int stride[1] = {4 * width};
    const int rows = sws_scale(sws, src, stride, 0, height, frame->data, frame->linesize);
    if (rows != height) throw RenderError("video: sws_scale returned " + std::to_string(rows) + " rows");
    frame->pts = frames;
    encode(frame);
    ++frames;
  }

  // flush the encoder and write the trailer: the file at `partial` is then a complete MP4
  void close() {
    if (headerWritten) {
      encode(nullptr);
      // rootsim's signature in the "comment" tag, with the hash of the packets written: the MP4 muxer
      // writes the metadata with the trailer (moov). The write rule (write_rule.hpp) replaces an MP4 at
      // a user's path only when it carries it and its packets still hash to it (checkMovieSignature)
      const std::string comment = std::string(outputSignatureText()) + " sha256:" + packets.hex();
      av_dict_set(&fmt->metadata, "comment", comment.c_str(), 0);
      check(av_write_trailer(fmt), "av_write_trailer(" + partial + ")");
      headerWritten = false;
    }
    if (ioOpen) {
      check(avio_closep(&fmt->pb), "avio_closep(" + partial + ")");
      ioOpen = false;
    }
  }

  void finish() {
    if (finished) return;
    close();
    finished = true;
    std::error_code ec;
    std::filesystem::rename(partial, path, ec);
    if (ec) throw RenderError("video: rename " + partial + " -> " + path + ": " + ec.message());
  }

  void release() {
    if (ioOpen && fmt) avio_closep(&fmt->pb);
    ioOpen = false;
    sws_freeContext(sws);
    sws = nullptr;
    av_packet_free(&pkt);
    av_frame_free(&frame);
    avcodec_free_context(&enc);
    avformat_free_context(fmt);
    fmt = nullptr;
  }

  ~Impl() {
    // without finish(): keep what was encoded as a playable "<path>.partial"
    if (!finished) {
      try {
        close();
      } catch (const std::exception&) {  // a destructor must not throw; the partial file stays
      }
    }
    release();
  }
};

VideoWriter::VideoWriter(const std::string& path, int width, int height, const VideoOptions& opt)
    : impl_(std::make_unique<Impl>(path, width, height, opt)) {}
VideoWriter::~VideoWriter() = default;
void VideoWriter::add(const Image& img) { impl_->add(img); }
void VideoWriter::finish() { impl_->finish(); }
int VideoWriter::frames() const { return impl_->frames; }

}  // namespace rootsim
