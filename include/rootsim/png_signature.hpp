#pragma once
// rootsim's signature in a PNG: a tEXt chunk "Software" = "rootsim-output rootsim <version> sha256:<H>"
// right after IHDR, H the SHA-256 of the IDAT chunks' data (the picture as compressed). The write rule
// (write_rule.hpp, whyNotSigned) replaces a PNG at a user's path only when it carries it, its chunks'
// CRCs hold and H matches. Header only (its includers link zlib, whose crc32 the chunks' CRCs are): the
// renderer (stb) and the figures (cairo) sign their PNGs.
#include <cstdint>
#include <string>

#include <zlib.h>

#include "rootsim/content_hash.hpp"
#include "rootsim/signature.hpp"

namespace rootsim {

namespace png_detail {
inline std::uint32_t be32(const std::string& s, std::size_t at) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(s[at])) << 24 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(s[at + 1])) << 16 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(s[at + 2])) << 8 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(s[at + 3]));
}
inline void putBe32(std::string& s, std::uint32_t v) {
  for (int k = 3; k >= 0; --k) s += static_cast<char>((v >> (8 * k)) & 0xff);
}
}  // namespace png_detail

// the PNG with a chunk of the given type (4 letters) and data inserted right after its IHDR, its CRC
// zlib's crc32 of type and data; a buffer that is not a PNG is returned as it is
inline std::string withChunkAfterIhdr(const std::string& png, const std::string& type, const std::string& data) {
  using namespace png_detail;
  constexpr std::size_t kIhdrEnd = 8 + 4 + 4 + 13 + 4;  // signature, IHDR length, type, data, CRC
  if (png.size() < kIhdrEnd || png.compare(12, 4, "IHDR") != 0) return png;
  const std::string body = type + data;
  std::string out = png.substr(0, kIhdrEnd);
  putBe32(out, static_cast<std::uint32_t>(data.size()));
  out += body;
  putBe32(out, static_cast<std::uint32_t>(
                   ::crc32(0, reinterpret_cast<const Bytef*>(body.data()), static_cast<uInt>(body.size()))));
  out += png.substr(kIhdrEnd);
  return out;
}

// the PNG with rootsim's signature chunk after its IHDR; a buffer that is not a PNG is returned as it is
inline std::string signPng(const std::string& png) {
  using namespace png_detail;
  constexpr std::size_t kIhdrEnd = 8 + 4 + 4 + 13 + 4;
  if (png.size() < kIhdrEnd || png.compare(12, 4, "IHDR") != 0) return png;
  Sha256 idat;
  for (std::size_t at = 8; at + 12 <= png.size();) {
    const std::uint32_t len = be32(png, at);
    if (len > png.size() - at - 12) break;
    if (png.compare(at + 4, 4, "IDAT") == 0) idat.update(png.data() + at + 8, len);
    at += 12 + len;
  }
  return withChunkAfterIhdr(png, "tEXt", std::string("Software") + '\0' + outputSignatureText() + " sha256:" + idat.hex());
}

}  // namespace rootsim
