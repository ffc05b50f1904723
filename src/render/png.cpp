// PNG files through libpng (png_encode.hpp writes them signed; libpng's simplified API reads them)
#include "rootsim/png.hpp"
#include "rootsim/png_encode.hpp"

#include <png.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <string>
#include <system_error>
#include <thread>

#include <unistd.h>

namespace rootsim {

namespace {

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
  // zlib level 1 with the "sub" filter: a frame written faster than at libpng's defaults, at a somewhat
  // larger file (docs/rendering.md, Speed)
  PngOptions o;
  o.compressionLevel = 1;
  o.filters = PNG_FILTER_SUB;
  std::string why;
  const std::string png = encodeSignedPng({img.rgba.data(), img.width, img.height, 4, 4 * static_cast<std::size_t>(img.width)}, o, &why);
  if (png.empty()) throw RenderError("writePng " + path + ": libpng: " + why);
  const std::string tmp = tempName(path);
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw RenderError("writePng " + path + ": cannot create " + tmp + ": " + std::strerror(errno));
  const bool written = std::fwrite(png.data(), 1, png.size(), f) == png.size();
  const int err = written ? 0 : errno;
  const bool closed = std::fclose(f) == 0;
  if (!written || !closed) {
    std::remove(tmp.c_str());
    throw RenderError("writePng " + path + ": write error: " + std::strerror(err ? err : EIO));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw RenderError("writePng " + path + ": rename from " + tmp + " failed: " + ec.message());
  }
}

Image readPng(const std::string& path) {
  png_image im{};
  im.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&im, path.c_str()))
    throw RenderError("readPng " + path + ": " + im.message);
  im.format = PNG_FORMAT_RGBA;
  Image img(static_cast<int>(im.width), static_cast<int>(im.height));
  if (!png_image_finish_read(&im, nullptr, img.rgba.data(), 0, nullptr)) {
    const std::string why = im.message;
    png_image_free(&im);
    throw RenderError("readPng " + path + ": " + why);
  }
  return img;
}

}  // namespace rootsim
