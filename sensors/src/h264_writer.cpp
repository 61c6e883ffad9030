// The preview video's H.264 encoder (see h264_writer.h).

#include "h264_writer.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <dlfcn.h>
#include <link.h>
#include <xmmintrin.h>

#include <cstdint>
#include <string>
#include <string_view>

#include "corsa/core/diagnostic.h"

namespace corsa::sensors::detail {
namespace {

// libx264's `veryfast` preset at its default quality (CRF 23): a preview to look at, not to
// measure from. With it the whole preview of a 31-frame demo run takes about 2.0 s of CPU against
// 4.5 s through OpenCV's writer (`medium` at OpenCV's bit rate). One encoder thread: with two,
// libx264's output was not the same bytes from one run to the next (three runs over the same 31
// frames gave three files); on one thread it is, and the caller overlaps its reading of the next
// frame with the encoding instead.
constexpr const char* kX264Preset = "veryfast";
constexpr const char* kX264Crf = "23";
constexpr int kX264Threads = 1;

/// The SSE control and status register at its power-on value (0x1F80: every exception masked,
/// round to nearest, neither flush-to-zero nor denormals-are-zero) for the life of the guard, put
/// back after. libx264 and swscale compute parts of the encoding in floating point, and the
/// thread that calls the writer may come with another register (oneTBB's workers have been seen
/// with flush-to-zero and denormals-are-zero set, and a thread starts with its creator's): with
/// the register fixed, the encoding does not depend on which thread calls it.
class DefaultFloatControl {
 public:
  DefaultFloatControl() : saved_(_mm_getcsr()) { _mm_setcsr(kDefault); }
  ~DefaultFloatControl() { _mm_setcsr(saved_); }
  DefaultFloatControl(const DefaultFloatControl&) = delete;
  DefaultFloatControl& operator=(const DefaultFloatControl&) = delete;

 private:
  static constexpr unsigned kDefault = 0x1F80;
  unsigned saved_;
};

/// libx264's flag for its AVX-512 code (X264_CPU_AVX512 of its x264.h).
constexpr uint32_t kX264CpuAvx512 = 1U << 16;

/// x264's `asm` option for the CPU flags libx264 detects here less AVX-512 ("asm=1111039" on this
/// machine's Xeon); empty when libx264's detection cannot be reached (it then uses every flag).
/// With AVX-512, libx264 on its one thread gave other bytes from the same frames (the same YUV
/// planes) now and then while the rendering ran beside it on two threads, never after the run;
/// without it (its AVX2 code for the same functions) every encode was the same bytes.
/// Those bytes are not the ones its AVX-512 code gives alone: the video is the same from run to
/// run, not the same as with every flag. libx264 is reached through the loaded library that holds
/// it (libavcodec's dependency; the plugin holding this writer is loaded with local symbols).
std::string x264_asm_without_avx512() {
  using CpuDetect = uint32_t (*)();
  void* detect = nullptr;
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* found) {
        const std::string_view name = info->dlpi_name == nullptr ? "" : info->dlpi_name;
        if (name.find("libx264.so") == std::string_view::npos) {
          return 0;
        }
        void* library = dlopen(info->dlpi_name, RTLD_NOW | RTLD_NOLOAD);
        if (library != nullptr) {
          *static_cast<void**>(found) = dlsym(library, "x264_cpu_detect");
          dlclose(library);  // RTLD_NOLOAD took a reference to the loaded library: given back
        }
        return 1;
      },
      static_cast<void*>(&detect));
  if (detect == nullptr) {
    detect = dlsym(RTLD_DEFAULT, "x264_cpu_detect");  // libx264 linked in statically
  }
  if (detect == nullptr) {
    return {};
  }
  return "asm=" + std::to_string(reinterpret_cast<CpuDetect>(detect)() & ~kX264CpuAvx512);
}

std::string av_error_text(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, text, sizeof text);
  return text;
}

}  // namespace

struct H264Writer::Codec {
  std::filesystem::path path;
  AVFormatContext* format = nullptr;
  AVCodecContext* context = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  SwsContext* to_yuv = nullptr;
  int64_t next_pts = 0;
  bool file_open = false;

  ~Codec() {
    sws_freeContext(to_yuv);
    av_packet_free(&packet);
    av_frame_free(&frame);
    avcodec_free_context(&context);
    if (format != nullptr) {
      if (file_open) {
        avio_closep(&format->pb);
      }
      avformat_free_context(format);
    }
  }

  [[noreturn]] void fail(const std::string& what, int code) const {
    throw InputError(make_error(
        path.string(), 0, "cannot write the preview video: " + what + ": " + av_error_text(code)));
  }
};

std::unique_ptr<H264Writer> H264Writer::open(const std::filesystem::path& path, cv::Size size,
                                             double fps) {
  const DefaultFloatControl float_control;
  const AVCodec* x264 = avcodec_find_encoder_by_name("libx264");
  if (x264 == nullptr || size.width <= 0 || size.height <= 0 || size.width % 2 != 0 ||
      size.height % 2 != 0 || !(fps > 0.0)) {
    return nullptr;
  }
  // libx264 reports its CPU flags and statistics at FFmpeg's "info" level; only errors matter
  // here. (OpenCV's FFmpeg backend sets the same level when it is first used.)
  av_log_set_level(AV_LOG_ERROR);
  auto codec = std::make_unique<Codec>();
  codec->path = path;
  if (avformat_alloc_output_context2(&codec->format, nullptr, "mp4", path.string().c_str()) < 0) {
    return nullptr;
  }
  // No library versions or times in the file: the same frames give the same bytes.
  codec->format->flags |= AVFMT_FLAG_BITEXACT;
  codec->stream = avformat_new_stream(codec->format, nullptr);
  codec->context = avcodec_alloc_context3(x264);
  codec->frame = av_frame_alloc();
  codec->packet = av_packet_alloc();
  if (codec->stream == nullptr || codec->context == nullptr || codec->frame == nullptr ||
      codec->packet == nullptr) {
    return nullptr;
  }
  AVCodecContext& c = *codec->context;
  c.width = size.width;
  c.height = size.height;
  c.framerate = av_d2q(fps, 1000000);
  c.time_base = av_inv_q(c.framerate);
  c.pix_fmt = AV_PIX_FMT_YUV420P;
  c.thread_count = kX264Threads;
  if (codec->format->oformat->flags & AVFMT_GLOBALHEADER) {
    c.flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  }
  AVDictionary* options = nullptr;
  av_dict_set(&options, "preset", kX264Preset, 0);
  av_dict_set(&options, "crf", kX264Crf, 0);
  static const std::string cpu_flags = x264_asm_without_avx512();
  if (!cpu_flags.empty()) {
    av_dict_set(&options, "x264-params", cpu_flags.c_str(), 0);
  }
  const int opened = avcodec_open2(&c, x264, &options);
  av_dict_free(&options);
  if (opened < 0 || avcodec_parameters_from_context(codec->stream->codecpar, &c) < 0) {
    return nullptr;
  }
  codec->stream->time_base = c.time_base;
  codec->frame->format = c.pix_fmt;
  codec->frame->width = c.width;
  codec->frame->height = c.height;
  if (av_frame_get_buffer(codec->frame, 0) < 0) {
    return nullptr;
  }
  // BGR to 4:2:0 YUV (BT.601, limited range) at the same size, as OpenCV's writer converts.
  codec->to_yuv = sws_getContext(c.width, c.height, AV_PIX_FMT_BGR24, c.width, c.height,
                                 AV_PIX_FMT_YUV420P, SWS_BICUBIC, nullptr, nullptr, nullptr);
  if (codec->to_yuv == nullptr) {
    return nullptr;
  }
  if (avio_open(&codec->format->pb, path.string().c_str(), AVIO_FLAG_WRITE) < 0) {
    return nullptr;
  }
  codec->file_open = true;
  if (avformat_write_header(codec->format, nullptr) < 0) {
    return nullptr;
  }
  return std::unique_ptr<H264Writer>(new H264Writer(std::move(codec)));
}

bool H264Writer::same_frame_rate(double a, double b) {
  return av_cmp_q(av_d2q(a, 1000000), av_d2q(b, 1000000)) == 0;
}

H264Writer::H264Writer(std::unique_ptr<Codec> codec) : codec_(std::move(codec)) {}

H264Writer::~H264Writer() = default;

void H264Writer::write(const cv::Mat& bgr) {
  const DefaultFloatControl float_control;
  Codec& k = *codec_;
  CV_Assert(bgr.type() == CV_8UC3 && bgr.cols == k.context->width && bgr.rows == k.context->height);
  int made_writable = av_frame_make_writable(k.frame);
  if (made_writable < 0) {
    k.fail("no frame buffer", made_writable);
  }
  const uint8_t* const source[1] = {bgr.data};
  const int source_stride[1] = {static_cast<int>(bgr.step[0])};
  sws_scale(k.to_yuv, source, source_stride, 0, bgr.rows, k.frame->data, k.frame->linesize);
  k.frame->pts = k.next_pts++;
  const int sent = avcodec_send_frame(k.context, k.frame);
  if (sent < 0) {
    k.fail("the encoder refused a frame", sent);
  }
  send(false);
}

void H264Writer::finish() {
  const DefaultFloatControl float_control;
  Codec& k = *codec_;
  const int sent = avcodec_send_frame(k.context, nullptr);
  if (sent < 0) {
    k.fail("the encoder did not flush", sent);
  }
  send(true);
  const int trailer = av_write_trailer(k.format);
  if (trailer < 0) {
    k.fail("cannot complete the file", trailer);
  }
  avio_closep(&k.format->pb);
  k.file_open = false;
}

// Moves every packet the encoder has ready into the file (all of them when flushing).
void H264Writer::send(bool flush) {
  Codec& k = *codec_;
  for (;;) {
    const int received = avcodec_receive_packet(k.context, k.packet);
    if (received == AVERROR(EAGAIN) || received == AVERROR_EOF) {
      if (received == AVERROR(EAGAIN) && flush) {
        k.fail("the encoder stopped before its last packet", received);
      }
      return;
    }
    if (received < 0) {
      k.fail("the encoder failed", received);
    }
    // Every frame lasts one frame period; without it the file's last frame has no duration and
    // players drop it.
    if (k.packet->duration == 0) {
      k.packet->duration = 1;
    }
    av_packet_rescale_ts(k.packet, k.context->time_base, k.stream->time_base);
    k.packet->stream_index = k.stream->index;
    const int written = av_interleaved_write_frame(k.format, k.packet);
    if (written < 0) {
      k.fail("cannot write a packet", written);
    }
  }
}

}  // namespace corsa::sensors::detail
