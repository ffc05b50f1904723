// read an MP4 back with libavformat/libavcodec: the tests' independent check of what VideoWriter made
extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/pixdesc.h>
#include <libswscale/swscale.h>
}

#include <memory>
#include <stdexcept>

#include "render_test_util.hpp"

namespace rtest {

Decoded decodeMp4(const std::string& path) {
  AVFormatContext* fmt = nullptr;
  if (avformat_open_input(&fmt, path.c_str(), nullptr, nullptr) < 0)
    throw std::runtime_error("decodeMp4: cannot open " + path);
  std::unique_ptr<AVFormatContext*, void (*)(AVFormatContext**)> fmtGuard(&fmt, avformat_close_input);
  if (avformat_find_stream_info(fmt, nullptr) < 0) throw std::runtime_error("decodeMp4: no stream info");
  const AVCodec* codec = nullptr;
  const int si = av_find_best_stream(fmt, AVMEDIA_TYPE_VIDEO, -1, -1, &codec, 0);
  if (si < 0 || !codec) throw std::runtime_error("decodeMp4: no video stream in " + path);
  const AVStream* st = fmt->streams[si];

  Decoded d;
  d.width = st->codecpar->width;
  d.height = st->codecpar->height;
  d.codec = avcodec_get_name(st->codecpar->codec_id);
  const char* pf = av_get_pix_fmt_name(static_cast<AVPixelFormat>(st->codecpar->format));
  d.pixFmt = pf ? pf : "?";
  d.colorspace = st->codecpar->color_space;
  d.durationS = fmt->duration > 0 ? static_cast<double>(fmt->duration) / AV_TIME_BASE : 0.0;

  AVCodecContext* dec = avcodec_alloc_context3(codec);
  std::unique_ptr<AVCodecContext*, void (*)(AVCodecContext**)> decGuard(&dec, avcodec_free_context);
  avcodec_parameters_to_context(dec, st->codecpar);
  dec->thread_count = 1;
  if (avcodec_open2(dec, codec, nullptr) < 0) throw std::runtime_error("decodeMp4: avcodec_open2 failed");
  AVPacket* pkt = av_packet_alloc();
  AVFrame* frame = av_frame_alloc();

  auto take = [&]() {
    while (avcodec_receive_frame(dec, frame) == 0) {
      if (d.frames == 0) {
        // back to RGBA with the BT.709 matrix the stream is tagged with
        d.first = rootsim::Image(frame->width, frame->height);
        SwsContext* sws = sws_getContext(frame->width, frame->height, static_cast<AVPixelFormat>(frame->format),
                                         frame->width, frame->height, AV_PIX_FMT_RGBA, SWS_BILINEAR, nullptr,
                                         nullptr, nullptr);
        const int* bt709 = sws_getCoefficients(SWS_CS_ITU709);
        sws_setColorspaceDetails(sws, bt709, 0, bt709, 1, 0, 1 << 16, 1 << 16);
        std::uint8_t* dst[1] = {d.first.rgba.data()};
        const int stride[1] = {4 * frame->width};
        sws_scale(sws, frame->data, frame->linesize, 0, frame->height, dst, stride);
        sws_freeContext(sws);
      }
      ++d.frames;
      av_frame_unref(frame);
    }
  };
  while (av_read_frame(fmt, pkt) >= 0) {
    if (pkt->stream_index == si) {
      avcodec_send_packet(dec, pkt);
      take();
    }
    av_packet_unref(pkt);
  }
  avcodec_send_packet(dec, nullptr);
  take();
  av_frame_free(&frame);
  av_packet_free(&pkt);
  return d;
}

}  // namespace rtest
