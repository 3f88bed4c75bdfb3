#include "animation_sinks.hpp"

#include <fcntl.h>
#include <gif_lib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "util/temp_files.hpp"

namespace softdrop::detail {
namespace {

std::runtime_error output_error(const std::string& path, const std::string& what) {
  return std::runtime_error("output '" + path + "': " + what);
}

void rename_over(const std::string& tmp, const std::string& path) {
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp);
    throw output_error(path, ec.message());
  }
}

class GifSink final : public FrameSink {
 public:
  GifSink(const std::string& path, int width, int height, double fps)
      : path_(path),
        tmp_name_(path),
        tmp_(tmp_name_.str()),
        width_(width),
        height_(height),
        delay_(std::max(2, static_cast<int>(std::lround(100.0 / fps)))),
        row_(static_cast<std::size_t>(width)) {
    if (width > 65535 || height > 65535) throw std::invalid_argument("size: too large for a GIF");
    // Opened here rather than by giflib, which would create the file readable by its owner only.
    const int fd = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);
    if (fd < 0) throw output_error(path_, "cannot write " + tmp_);
    int error = 0;
    gif_ = EGifOpenFileHandle(fd, &error);
    if (!gif_) {
      ::close(fd);
      throw failed(std::string("cannot write (") + GifErrorString(error) + ")");
    }
    // Drawings have few colours, so a fixed palette with nearest-entry mapping is enough (no
    // dithering, no per-frame quantisation): the 6 x 6 x 6 colour cube and 40 greys.
    GifColorType colours[256];
    for (int i = 0; i < 216; ++i)
      colours[i] = {static_cast<GifByteType>(51 * (i / 36)), static_cast<GifByteType>(51 * (i / 6 % 6)),
                    static_cast<GifByteType>(51 * (i % 6))};
    for (int i = 216; i < 256; ++i) {
      const auto v = static_cast<GifByteType>(std::lround((i - 216) * 255.0 / 39));
      colours[i] = {v, v, v};
    }
    ColorMapObject* map = GifMakeMapObject(256, colours);
    const bool ok = EGifPutScreenDesc(gif_, width, height, 8, 0, map) == GIF_OK;
    GifFreeMapObject(map);
    if (!ok) throw failed("GIF screen descriptor");
    EGifSetGifVersion(gif_, true);
    // Loop forever (NETSCAPE2.0 application extension).
    const unsigned char loop_app[] = {'N', 'E', 'T', 'S', 'C', 'A', 'P', 'E', '2', '.', '0'};
    const unsigned char loop_data[] = {1, 0, 0};
    if (EGifPutExtensionLeader(gif_, APPLICATION_EXT_FUNC_CODE) != GIF_OK ||
        EGifPutExtensionBlock(gif_, sizeof loop_app, loop_app) != GIF_OK ||
        EGifPutExtensionBlock(gif_, sizeof loop_data, loop_data) != GIF_OK || EGifPutExtensionTrailer(gif_) != GIF_OK)
      throw failed("GIF loop extension");
  }
  ~GifSink() override {
    if (gif_) {
      int error = 0;
      EGifCloseFile(gif_, &error);
      std::filesystem::remove(tmp_);
    }
  }

  void add(const unsigned char* data, int stride) override {
    GraphicsControlBlock gcb{};
    gcb.DisposalMode = DISPOSE_DO_NOT;
    gcb.DelayTime = delay_;
    gcb.TransparentColor = NO_TRANSPARENT_COLOR;
    GifByteType ext[4];
    const std::size_t n = EGifGCBToExtension(&gcb, ext);
    if (EGifPutExtension(gif_, GRAPHICS_EXT_FUNC_CODE, static_cast<int>(n), ext) != GIF_OK ||
        EGifPutImageDesc(gif_, 0, 0, width_, height_, false, nullptr) != GIF_OK)
      throw failed("GIF frame header");
    for (int y = 0; y < height_; ++y) {
      const auto* px = reinterpret_cast<const std::uint32_t*>(data + static_cast<std::ptrdiff_t>(y) * stride);
      for (int x = 0; x < width_; ++x) {
        const int r = static_cast<int>((px[x] >> 16) & 0xff), g = static_cast<int>((px[x] >> 8) & 0xff),
                  b = static_cast<int>(px[x] & 0xff);
        const int index = std::abs(r - g) < 8 && std::abs(g - b) < 8
                              ? 216 + static_cast<int>(std::lround((r + g + b) / 3.0 * 39 / 255))
                              : 36 * ((r + 25) / 51) + 6 * ((g + 25) / 51) + (b + 25) / 51;
        row_[static_cast<std::size_t>(x)] = static_cast<GifByteType>(index);
      }
      if (EGifPutLine(gif_, row_.data(), width_) != GIF_OK) throw failed("GIF pixels");
    }
  }

  void finish() override {
    int error = 0;
    const int status = EGifCloseFile(gif_, &error);
    gif_ = nullptr;
    if (status != GIF_OK) {
      std::filesystem::remove(tmp_);
      throw output_error(path_, std::string("GIF close (") + GifErrorString(error) + ")");
    }
    rename_over(tmp_, path_);
  }

 private:
  std::runtime_error failed(const std::string& what) { return output_error(path_, what); }

  std::string path_;
  detail::TempName tmp_name_;
  std::string tmp_;
  int width_, height_, delay_;
  std::vector<GifByteType> row_;
  GifFileType* gif_ = nullptr;
};

// Single quotes for the shell: 'it'\''s'.
std::string shell_quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

class VideoSink final : public FrameSink {
 public:
  VideoSink(const std::string& path, int width, int height, double fps)
      : path_(path), tmp_name_(path), tmp_(tmp_name_.str()), width_(width), height_(height) {
    if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0)
      throw output_error(path_, "writing .mp4 needs the ffmpeg program (apt-get install ffmpeg), or use .gif");
    // H.264 wants even sizes; render_animation makes them so (the pad filter is a no-op then).
    const std::string command = "ffmpeg -loglevel error -y -f rawvideo -pixel_format bgr0 -video_size " +
                                std::to_string(width) + "x" + std::to_string(height) + " -framerate " +
                                std::to_string(fps) + " -i - -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -c:v libx264 " +
                                "-pix_fmt yuv420p -f mp4 " + shell_quoted(tmp_) + " 2>&1";
    pipe_ = ::popen(command.c_str(), "w");
    if (!pipe_) throw output_error(path_, "cannot start ffmpeg");
  }
  ~VideoSink() override {
    if (pipe_) {
      ::pclose(pipe_);
      std::filesystem::remove(tmp_);
    }
  }

  void add(const unsigned char* data, int stride) override {
    for (int y = 0; y < height_; ++y)
      if (std::fwrite(data + static_cast<std::ptrdiff_t>(y) * stride, 4, static_cast<std::size_t>(width_), pipe_) !=
          static_cast<std::size_t>(width_))
        throw output_error(path_, "ffmpeg stopped reading frames");
  }

  void finish() override {
    const int status = ::pclose(pipe_);
    pipe_ = nullptr;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      std::filesystem::remove(tmp_);
      throw output_error(path_, "ffmpeg failed (exit status " + std::to_string(WEXITSTATUS(status)) + ")");
    }
    rename_over(tmp_, path_);
  }

 private:
  std::string path_;
  detail::TempName tmp_name_;
  std::string tmp_;
  int width_, height_;
  FILE* pipe_ = nullptr;
};

}  // namespace

std::unique_ptr<FrameSink> gif_sink(const std::string& path, int width, int height, double fps) {
  return std::make_unique<GifSink>(path, width, height, fps);
}

std::unique_ptr<FrameSink> video_sink(const std::string& path, int width, int height, double fps) {
  return std::make_unique<VideoSink>(path, width, height, fps);
}

}  // namespace softdrop::detail
