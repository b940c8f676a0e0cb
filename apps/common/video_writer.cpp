#include "video_writer.hpp"

#include <s2sim/error.hpp>

#ifdef S2SIM_HAVE_VIDEO
extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}
#endif

namespace s2sim::apps {

#ifdef S2SIM_HAVE_VIDEO

bool video_supported() {
  return true;
}

struct VideoWriter::Impl {
  std::string file;
  int width = 0, height = 0, source_width = 0;
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  SwsContext* scale = nullptr;
  bool header_written = false;

  Error fail(const std::string& what, int code = 0) const {
    std::string text = what;
    if (code < 0) {
      char reason[AV_ERROR_MAX_STRING_SIZE] = {};
      av_strerror(code, reason, sizeof reason);
      text += std::string(": ") + reason;
    }
    return Error(ErrorKind::usage, "--video '" + file + "': " + text);
  }

  /// Sends `f` (nullptr: flush) and writes every packet the encoder has ready.
  void encode(AVFrame* f) {
    int status = avcodec_send_frame(codec, f);
    if (status < 0) throw fail("encoding a frame failed", status);
    for (;;) {
      status = avcodec_receive_packet(codec, packet);
      if (status == AVERROR(EAGAIN) || status == AVERROR_EOF) return;
      if (status < 0) throw fail("encoding a frame failed", status);
      // Every frame lasts one period: without it the MP4's edit list ends at the last
      // frame's start, and players (and decoders honouring it) drop that frame.
      if (packet->duration == 0) packet->duration = 1;
      av_packet_rescale_ts(packet, codec->time_base, stream->time_base);
      packet->stream_index = stream->index;
      status = av_interleaved_write_frame(format, packet);
      av_packet_unref(packet);
      if (status < 0) throw fail("writing a frame failed", status);
    }
  }

  ~Impl() {
    sws_freeContext(scale);
    av_packet_free(&packet);
    av_frame_free(&frame);
    avcodec_free_context(&codec);
    if (format != nullptr && !(format->oformat->flags & AVFMT_NOFILE)) avio_closep(&format->pb);
    avformat_free_context(format);
  }
};

VideoWriter::VideoWriter(const std::string& file, int width_px, int height_px, int fps)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  av_log_set_level(AV_LOG_ERROR);  // the encoder's statistics are not the user's business
  m.file = file;
  m.source_width = width_px;
  m.width = width_px & ~1;  // 4:2:0 needs even sizes
  m.height = height_px & ~1;
  if (m.width < 2 || m.height < 2) throw m.fail("the window is too small for a video");
  int status = avformat_alloc_output_context2(&m.format, nullptr, nullptr, file.c_str());
  if (status < 0 || m.format == nullptr)
    throw m.fail("no video format for this file name (use .mp4)", status);
  const AVCodec* encoder = avcodec_find_encoder_by_name("libx264");
  if (encoder == nullptr) encoder = avcodec_find_encoder(AV_CODEC_ID_MPEG4);
  if (encoder == nullptr) throw m.fail("libavcodec has neither an H.264 nor an MPEG-4 encoder");
  codec_ = encoder->name;
  m.stream = avformat_new_stream(m.format, nullptr);
  m.codec = avcodec_alloc_context3(encoder);
  m.frame = av_frame_alloc();
  m.packet = av_packet_alloc();
  if (m.stream == nullptr || m.codec == nullptr || m.frame == nullptr || m.packet == nullptr)
    throw m.fail("out of memory");
  m.codec->width = m.width;
  m.codec->height = m.height;
  m.codec->time_base = AVRational{1, fps};
  m.codec->framerate = AVRational{fps, 1};
  m.codec->pix_fmt = AV_PIX_FMT_YUV420P;
  m.codec->gop_size = fps;
  if (codec_ == "libx264") {
    av_opt_set(m.codec->priv_data, "preset", "veryfast", 0);
    av_opt_set(m.codec->priv_data, "crf", "20", 0);
  } else {
    m.codec->bit_rate = static_cast<std::int64_t>(m.width) * m.height * fps / 4;
  }
  if (m.format->oformat->flags & AVFMT_GLOBALHEADER) m.codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  if ((status = avcodec_open2(m.codec, encoder, nullptr)) < 0)
    throw m.fail("cannot open the encoder " + codec_, status);
  if ((status = avcodec_parameters_from_context(m.stream->codecpar, m.codec)) < 0)
    throw m.fail("cannot set the stream's parameters", status);
  m.stream->time_base = m.codec->time_base;
  if (!(m.format->oformat->flags & AVFMT_NOFILE) &&
      (status = avio_open(&m.format->pb, file.c_str(), AVIO_FLAG_WRITE)) < 0)
    throw m.fail("cannot create the file", status);
  if ((status = avformat_write_header(m.format, nullptr)) < 0)
    throw m.fail("cannot write the header", status);
  m.header_written = true;
  m.frame->format = m.codec->pix_fmt;
  m.frame->width = m.width;
  m.frame->height = m.height;
  if ((status = av_frame_get_buffer(m.frame, 0)) < 0) throw m.fail("out of memory", status);
  m.scale = sws_getContext(m.width, m.height, AV_PIX_FMT_RGB24, m.width, m.height,
                           AV_PIX_FMT_YUV420P, SWS_BICUBIC, nullptr, nullptr, nullptr);
  if (m.scale == nullptr) throw m.fail("no RGB to YUV conversion");
}

VideoWriter::~VideoWriter() = default;

void VideoWriter::add_frame(const unsigned char* rgb_bottom_up) {
  const int stride = 3 * impl_->source_width;
  // The top row is the last one OpenGL read: start there and walk the rows backwards.
  add_frame_rows(rgb_bottom_up + static_cast<std::ptrdiff_t>(impl_->height - 1) * stride, -stride);
}

void VideoWriter::add_frame_rows(const unsigned char* top_row, int stride_bytes) {
  Impl& m = *impl_;
  int status = av_frame_make_writable(m.frame);
  if (status < 0) throw m.fail("out of memory", status);
  const std::uint8_t* rows[1] = {top_row};
  const int strides[1] = {stride_bytes};
  sws_scale(m.scale, rows, strides, 0, m.height, m.frame->data, m.frame->linesize);
  m.frame->pts = frames_++;
  m.encode(m.frame);
}

void VideoWriter::finish() {
  Impl& m = *impl_;
  if (!m.header_written) return;
  m.encode(nullptr);
  const int status = av_write_trailer(m.format);
  m.header_written = false;
  if (status < 0) throw m.fail("cannot finish the file", status);
}

#else  // built without libavcodec

bool video_supported() {
  return false;
}

struct VideoWriter::Impl {};

VideoWriter::VideoWriter(const std::string& file, int, int, int) {
  throw Error(ErrorKind::usage,
              "--video '" + file +
                  "': this program was built without libavcodec (install libavcodec-dev, "
                  "libavformat-dev and libswscale-dev, then build again)");
}
VideoWriter::~VideoWriter() = default;
void VideoWriter::add_frame(const unsigned char*) {}
void VideoWriter::add_frame_rows(const unsigned char*, int) {}
void VideoWriter::finish() {}

#endif

}  // namespace s2sim::apps
