// H.264 MP4 through libavcodec (libx264) and libavformat; RGBA -> yuv420p BT.709 with swscale
#include "rootsim/video_writer.hpp"
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

}  // namespace

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

    // rootsim's signature in the "comment" tag: the write rule (write_rule.hpp) replaces an MP4 at a
    // user's path only when it carries it
    av_dict_set(&fmt->metadata, "comment", outputSignatureText(), 0);
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
