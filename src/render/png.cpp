// PNG files through stb (libstb ships the compiled implementation: no STB_*_IMPLEMENTATION here)
#include "rootsim/png.hpp"
#include "rootsim/png_signature.hpp"

#include <stb_image.h>
#include <stb_image_write.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <system_error>
#include <thread>
#include <cstdint>
#include <string>

#include <unistd.h>

namespace rootsim {

namespace {

// stb's PNG settings are globals: set them once. Level 1 with the "sub" filter writes a frame faster
// than stb's defaults at a slightly larger file (docs/rendering.md, Pitfalls).
void configureStb() {
  static std::once_flag once;
  std::call_once(once, [] {
    stbi_write_png_compression_level = 1;
    stbi_write_force_png_filter = 1;
  });
}

// stb hands over the whole PNG in one call: kept, then written signed (png_signature.hpp)
struct FileSink {
  std::string bytes;
};
void writeToFile(void* ctx, void* data, int size) {
  if (size > 0) static_cast<FileSink*>(ctx)->bytes.append(static_cast<const char*>(data), static_cast<std::size_t>(size));
}

// a temporary name beside path, unique per process and thread
std::string tempName(const std::string& path) {
  return path + ".tmp" + std::to_string(::getpid()) + "-" +
         std::to_string(std::hash<std::thread::id>{}(std::this_thread::get_id()) % 100000);
}

}  // namespace

void writePng(const std::string& path, const Image& img) {
  if (img.width <= 0 || img.height <= 0 ||
      img.rgba.size() != static_cast<std::size_t>(4) * img.width * img.height)
    throw RenderError("writePng " + path + ": image " + std::to_string(img.width) + "x" +
                      std::to_string(img.height) + " with " + std::to_string(img.rgba.size()) +
                      " bytes is not a valid RGBA picture");
  configureStb();
  const std::string tmp = tempName(path);
  FileSink sink;
  const int ok = stbi_write_png_to_func(writeToFile, &sink, img.width, img.height, 4, img.rgba.data(),
                                        4 * img.width);
  if (!ok) throw RenderError("writePng " + path + ": stbi_write_png_to_func failed");
  const std::string signedPng = signPng(sink.bytes);
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw RenderError("writePng " + path + ": cannot create " + tmp + ": " + std::strerror(errno));
  const bool written = std::fwrite(signedPng.data(), 1, signedPng.size(), f) == signedPng.size();
  const int err = written ? 0 : errno;
  const bool closed = std::fclose(f) == 0;
  if (!written || !closed) {
    std::remove(tmp.c_str());
    throw RenderError("writePng " + path + ": " +
                      (!ok ? std::string("stbi_write_png_to_func failed")
                           : std::string("write error: ") + std::strerror(err ? err : EIO)));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw RenderError("writePng " + path + ": rename from " + tmp + " failed: " + ec.message());
  }
}

Image readPng(const std::string& path) {
  int w = 0, h = 0, channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &channels, 4);
  if (!data) {
    const char* why = stbi_failure_reason();
    throw RenderError("readPng " + path + ": " + (why ? why : "stbi_load failed"));
  }
  Image img(w, h);
  std::memcpy(img.rgba.data(), data, img.rgba.size());
  stbi_image_free(data);
  return img;
}

}  // namespace rootsim
