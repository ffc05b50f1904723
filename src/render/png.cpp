// PNG files through stb (libstb ships the compiled implementation: no STB_*_IMPLEMENTATION here)
#include "rootsim/png.hpp"
#include "rootsim/signature.hpp"

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

// stb's PNG settings are globals: set them once. Level 1 with the "sub" filter writes a 1080p frame
// about 3x faster than stb's defaults (docs/rendering.md, Pitfalls) at a slightly larger file.
void configureStb() {
  static std::once_flag once;
  std::call_once(once, [] {
    stbi_write_png_compression_level = 1;
    stbi_write_force_png_filter = 1;
  });
}

struct FileSink {
  std::FILE* f = nullptr;
  bool failed = false;
};

// CRC-32 of a PNG chunk (ISO 3309, the polynomial PNG specifies)
std::uint32_t crc32(const unsigned char* p, std::size_t n, std::uint32_t c = 0xffffffffu) {
  for (std::size_t i = 0; i < n; ++i) {
    c ^= p[i];
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return c;
}

// the tEXt chunk "Software" = rootsim's signature: the write rule (write_rule.hpp) replaces a PNG at a
// user's path only when it carries it
std::string signatureChunk() {
  const std::string body = std::string("tEXt") + "Software" + '\0' + outputSignatureText();
  std::string chunk;
  const std::uint32_t len = static_cast<std::uint32_t>(body.size() - 4);
  for (int k = 3; k >= 0; --k) chunk += static_cast<char>((len >> (8 * k)) & 0xff);
  chunk += body;
  const std::uint32_t crc = crc32(reinterpret_cast<const unsigned char*>(body.data()), body.size()) ^ 0xffffffffu;
  for (int k = 3; k >= 0; --k) chunk += static_cast<char>((crc >> (8 * k)) & 0xff);
  return chunk;
}

// stb hands over the whole PNG in one call: written with the signature chunk after IHDR (the PNG
// signature, 8 bytes, and the IHDR chunk, 25 bytes)
void writeToFile(void* ctx, void* data, int size) {
  auto* sink = static_cast<FileSink*>(ctx);
  if (sink->failed || size <= 0) return;
  constexpr int kHead = 8 + 25;
  static const std::string chunk = signatureChunk();
  const auto* bytes = static_cast<const unsigned char*>(data);
  const bool split = size > kHead;
  const std::size_t first = split ? kHead : static_cast<std::size_t>(size);
  bool ok = std::fwrite(bytes, 1, first, sink->f) == first;
  if (split) {
    ok = ok && std::fwrite(chunk.data(), 1, chunk.size(), sink->f) == chunk.size();
    const std::size_t rest = static_cast<std::size_t>(size) - first;
    ok = ok && std::fwrite(bytes + first, 1, rest, sink->f) == rest;
  }
  if (!ok) sink->failed = true;
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
  sink.f = std::fopen(tmp.c_str(), "wb");
  if (!sink.f)
    throw RenderError("writePng " + path + ": cannot create " + tmp + ": " + std::strerror(errno));
  const int ok = stbi_write_png_to_func(writeToFile, &sink, img.width, img.height, 4, img.rgba.data(),
                                        4 * img.width);
  const int err = sink.failed ? errno : 0;
  const bool closed = std::fclose(sink.f) == 0;
  if (!ok || sink.failed || !closed) {
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
