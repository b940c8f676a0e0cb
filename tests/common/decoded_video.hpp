#pragma once
/// \file
/// Every frame of an MP4 decoded through libavcodec, for tests of the videos S2Sim writes
/// (s2sim-view --replay --video, s2sim-run --video). Link libavcodec, libavformat, libavutil.

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
}

#include <filesystem>
#include <string>

namespace s2sim::test {

struct Decoded {
  int width = 0, height = 0, frames = 0, packets = 0;
  std::string codec;
};

/// Every frame of a video, decoded.
inline Decoded decode(const std::filesystem::path& file) {
  Decoded d;
  AVFormatContext* format = nullptr;
  if (avformat_open_input(&format, file.string().c_str(), nullptr, nullptr) < 0) return d;
  avformat_find_stream_info(format, nullptr);
  const int stream = av_find_best_stream(format, AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
  if (stream >= 0) {
    const AVCodecParameters* par = format->streams[stream]->codecpar;
    const AVCodec* decoder = avcodec_find_decoder(par->codec_id);
    AVCodecContext* codec = avcodec_alloc_context3(decoder);
    avcodec_parameters_to_context(codec, par);
    avcodec_open2(codec, decoder, nullptr);
    d.codec = decoder->name;
    AVPacket* packet = av_packet_alloc();
    AVFrame* frame = av_frame_alloc();
    auto drain = [&] {
      while (avcodec_receive_frame(codec, frame) == 0) {
        ++d.frames;
        d.width = frame->width;
        d.height = frame->height;
      }
    };
    while (av_read_frame(format, packet) >= 0) {
      if (packet->stream_index == stream) {
        ++d.packets;
        while (avcodec_send_packet(codec, packet) == AVERROR(EAGAIN))
          drain();
        drain();
      }
      av_packet_unref(packet);
    }
    avcodec_send_packet(codec, nullptr);
    drain();
    av_frame_free(&frame);
    av_packet_free(&packet);
    avcodec_free_context(&codec);
  }
  avformat_close_input(&format);
  return d;
}

}  // namespace s2sim::test
