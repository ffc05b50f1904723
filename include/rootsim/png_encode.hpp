#pragma once
// PNG files as rootsim writes them, encoded by libpng: 8-bit RGB or RGBA rows, an optional pHYs chunk
// (the resolution) and bKGD chunk (a white background), and rootsim's signature, a tEXt chunk
// "Software" = "rootsim-output rootsim <version> sha256:<H>" after the image data, H the SHA-256 of the
// IDAT chunks' data (the picture as compressed). The write rule (write_rule.hpp, whyNotSigned) replaces
// a PNG at a user's path only when it carries it, its chunks' CRCs hold and H matches. Header only (its
// includers link libpng and libcrypto): the renderer and the figures write with it without linking
// rootsim_io.
#include <png.h>

#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <string>

#include "rootsim/content_hash.hpp"
#include "rootsim/signature.hpp"

namespace rootsim {

// the pixels to encode: height rows of width pixels, channels (3: RGB, 4: RGBA) bytes each, row y at
// data + y * stride
struct PngPixels {
  const unsigned char* data = nullptr;
  int width = 0, height = 0;
  int channels = 4;
  std::size_t stride = 0;
};

// how to encode them; the defaults are libpng's own (its zlib level and adaptive filters)
struct PngOptions {
  int compressionLevel = -1;      // zlib's 0..9; -1: libpng's default
  int filters = -1;               // a PNG_FILTER_* mask; -1: libpng's default
  double dpi = 0;                 // > 0: a pHYs chunk in pixels per metre (rounded)
  bool whiteBackground = false;   // a bKGD chunk: white
};

namespace png_detail {

inline std::uint32_t be32(const std::string& s, std::size_t at) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(s[at])) << 24 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(s[at + 1])) << 16 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(s[at + 2])) << 8 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(s[at + 3]));
}

// libpng's callbacks: output appended to a string; an error's message kept, then libpng's longjmp
inline void append(png_structp png, png_bytep data, png_size_t n) {
  static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(data), n);
}
inline void noFlush(png_structp) {}
inline void onError(png_structp png, png_const_charp message) {
  static_cast<std::string*>(png_get_error_ptr(png))->assign(message);
  png_longjmp(png, 1);
}
inline void onWarning(png_structp, png_const_charp) {}

// the header chunks and the rows (libpng finishes the IDAT stream with the last row); false after an
// error. No object with a destructor lives between setjmp and libpng's longjmp.
inline bool writeImage(png_structp png, png_infop info, const PngPixels& px, const PngOptions& o) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_IHDR(png, info, static_cast<png_uint_32>(px.width), static_cast<png_uint_32>(px.height), 8,
               px.channels == 4 ? PNG_COLOR_TYPE_RGB_ALPHA : PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (o.compressionLevel >= 0) png_set_compression_level(png, o.compressionLevel);
  if (o.filters >= 0) png_set_filter(png, PNG_FILTER_TYPE_BASE, o.filters);
  if (o.whiteBackground) {
    png_color_16 white{};
    white.red = white.green = white.blue = white.gray = 255;
    png_set_bKGD(png, info, &white);
  }
  if (o.dpi > 0) {
    const auto ppm = static_cast<png_uint_32>(std::lround(o.dpi / 0.0254));
    png_set_pHYs(png, info, ppm, ppm, PNG_RESOLUTION_METER);
  }
  png_write_info(png, info);
  for (int y = 0; y < px.height; ++y) png_write_row(png, px.data + static_cast<std::size_t>(y) * px.stride);
  return true;
}

// the signature's tEXt chunk (set after the rows: libpng writes it after the IDAT chunks) and IEND
inline bool writeEnd(png_structp png, png_infop info, png_text* text) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_text(png, info, text, 1);
  png_write_end(png, info);
  return true;
}

// SHA-256 of the data of the IDAT chunks in a PNG byte string (walked up to its end)
inline std::string idatSha256(const std::string& png) {
  Sha256 idat;
  for (std::size_t at = 8; at + 12 <= png.size();) {
    const std::uint32_t len = be32(png, at);
    if (len > png.size() - at - 12) break;
    if (png.compare(at + 4, 4, "IDAT") == 0) idat.update(png.data() + at + 8, len);
    at += 12 + len;
  }
  return idat.hex();
}

// frees libpng's structures on every path out
struct WriteStructs {
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~WriteStructs() { png_destroy_write_struct(&png, info ? &info : nullptr); }
};

}  // namespace png_detail

// the PNG file of px, signed; "" with *why set when libpng refuses (a size or channel count it cannot
// write, no memory)
inline std::string encodeSignedPng(const PngPixels& px, const PngOptions& o, std::string* why) {
  using namespace png_detail;
  if (px.data == nullptr || px.width <= 0 || px.height <= 0 || (px.channels != 3 && px.channels != 4) ||
      px.stride < static_cast<std::size_t>(px.width) * static_cast<std::size_t>(px.channels)) {
    *why = "not a picture: " + std::to_string(px.width) + "x" + std::to_string(px.height) + " pixels of " +
           std::to_string(px.channels) + " bytes, rows " + std::to_string(px.stride) + " bytes apart";
    return "";
  }
  std::string out;
  WriteStructs s;
  s.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, why, onError, onWarning);
  if (s.png) s.info = png_create_info_struct(s.png);
  if (!s.png || !s.info) {
    *why = "libpng could not start (no memory)";
    return "";
  }
  png_set_write_fn(s.png, &out, append, noFlush);
  if (!writeImage(s.png, s.info, px, o)) return "";
  std::string software = std::string(outputSignatureText()) + " sha256:" + idatSha256(out);
  char key[] = "Software";
  png_text text{};
  text.compression = PNG_TEXT_COMPRESSION_NONE;
  text.key = key;
  text.text = software.data();
  text.text_length = software.size();
  if (!writeEnd(s.png, s.info, &text)) return "";
  return out;
}

}  // namespace rootsim
