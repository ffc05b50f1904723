// PNG files as rootsim writes them (include/rootsim/png_encode.hpp, header only): libpng's encoding decodes
// to the very pixels given, the pHYs and bKGD chunks hold what was asked, the signature's tEXt chunk
// follows the image data and the write rule (whyNotSigned) takes the file for rootsim's, and a picture
// libpng cannot write is refused with why.
#include <doctest/doctest.h>

#include <png.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "rootsim/png_encode.hpp"
#include "rootsim/write_rule.hpp"
#include "test_support.hpp"

using namespace rootsim;
namespace fs = std::filesystem;

namespace {
fs::path scratch(const std::string& name) { return rootsim::test::scratchDir("png_encode", name); }

// a picture of w x h pixels of `channels` bytes in which every byte differs from its neighbours
std::vector<unsigned char> pattern(int w, int h, int channels) {
  std::vector<unsigned char> px(static_cast<std::size_t>(w) * h * channels);
  for (std::size_t i = 0; i < px.size(); ++i) px[i] = static_cast<unsigned char>((i * 37 + i / 7) & 0xff);
  return px;
}

// a PNG's chunks in order: type and data
std::vector<std::pair<std::string, std::string>> chunks(const std::string& png) {
  std::vector<std::pair<std::string, std::string>> out;
  for (std::size_t at = 8; at + 12 <= png.size();) {
    const std::uint32_t len = png_detail::be32(png, at);
    REQUIRE(len <= png.size() - at - 12);
    out.emplace_back(png.substr(at + 4, 4), png.substr(at + 8, len));
    at += 12 + len;
  }
  return out;
}

// the pixels libpng decodes from a PNG in memory, as `format` (PNG_FORMAT_RGB or PNG_FORMAT_RGBA)
std::vector<unsigned char> decoded(const std::string& png, png_uint_32 format, int* w, int* h) {
  png_image im{};
  im.version = PNG_IMAGE_VERSION;
  REQUIRE(png_image_begin_read_from_memory(&im, png.data(), png.size()) != 0);
  im.format = format;
  std::vector<unsigned char> px(PNG_IMAGE_SIZE(im));
  REQUIRE(png_image_finish_read(&im, nullptr, px.data(), 0, nullptr) != 0);
  *w = static_cast<int>(im.width), *h = static_cast<int>(im.height);
  return px;
}
}  // namespace

TEST_CASE("png_encode: RGBA and RGB rows decode to the same pixels, with rows padded apart too") {
  for (int channels : {3, 4}) {
    CAPTURE(channels);
    const int w = 37, h = 11;
    const std::vector<unsigned char> px = pattern(w, h, channels);
    std::string why;
    const std::string png = encodeSignedPng({px.data(), w, h, channels, static_cast<std::size_t>(w) * channels}, {}, &why);
    REQUIRE_MESSAGE(!png.empty(), why);
    CHECK(png.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0);
    int dw = 0, dh = 0;
    CHECK(decoded(png, channels == 4 ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB, &dw, &dh) == px);
    CHECK(dw == w);
    CHECK(dh == h);
    // the same rows 5 bytes apart more than their width: the padding is not written
    const std::size_t stride = static_cast<std::size_t>(w) * channels + 5;
    std::vector<unsigned char> padded(stride * h, 0xee);
    for (int y = 0; y < h; ++y)
      std::copy_n(px.data() + static_cast<std::size_t>(y) * w * channels, w * channels, padded.data() + y * stride);
    CHECK(encodeSignedPng({padded.data(), w, h, channels, stride}, {}, &why) == png);
    // level 1 and the "sub" filter (the renderer's frames): other bytes, the same pixels
    PngOptions fast;
    fast.compressionLevel = 1;
    fast.filters = PNG_FILTER_SUB;
    const std::string quick = encodeSignedPng({px.data(), w, h, channels, static_cast<std::size_t>(w) * channels}, fast, &why);
    CHECK(decoded(quick, channels == 4 ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB, &dw, &dh) == px);
  }
}

TEST_CASE("png_encode: chunks IHDR, bKGD white, pHYs at the dpi asked, IDAT, the signature's tEXt, IEND") {
  const std::vector<unsigned char> px = pattern(20, 10, 3);
  PngOptions o;
  o.dpi = 300;
  o.whiteBackground = true;
  std::string why;
  const std::string png = encodeSignedPng({px.data(), 20, 10, 3, 60}, o, &why);
  const auto c = chunks(png);
  REQUIRE(c.size() == 6);
  CHECK(c[0].first == "IHDR");
  CHECK(c[1].first == "bKGD");
  CHECK(c[1].second == std::string("\0\xff\0\xff\0\xff", 6));  // 16-bit red, green, blue: 255
  CHECK(c[2].first == "pHYs");
  // 300 dpi = 11811.02 pixels per metre, rounded; unit byte 1: the metre
  CHECK(c[2].second == std::string("\0\0\x2e\x23\0\0\x2e\x23\x01", 9));
  CHECK(c[3].first == "IDAT");
  CHECK(c[4].first == "tEXt");
  Sha256 idat;
  idat.update(c[3].second);
  CHECK(c[4].second == std::string("Software") + '\0' + outputSignatureText() + " sha256:" + idat.hex());
  CHECK(c[5].first == "IEND");
  // without them: no pHYs, no bKGD
  const auto plain = chunks(encodeSignedPng({px.data(), 20, 10, 3, 60}, {}, &why));
  REQUIRE(plain.size() == 4);
  CHECK(plain[1].first == "IDAT");
}

TEST_CASE("png_encode: the write rule takes the file for rootsim's, and not once a pixel changed") {
  const fs::path d = scratch("signed");
  const int w = 64, h = 48;
  const std::vector<unsigned char> px = pattern(w, h, 4);
  std::string why;
  const std::string png = encodeSignedPng({px.data(), w, h, 4, static_cast<std::size_t>(w) * 4}, {}, &why);
  { std::ofstream(d / "a.png", std::ios::binary) << png; }
  CHECK(whyNotSigned(d / "a.png", OutputFormat::Png) == "");
  // another picture's data under this signature: the IDAT of b, its CRC right, the hash not
  std::vector<unsigned char> other = px;
  other[100] ^= 1;
  const std::string b = encodeSignedPng({other.data(), w, h, 4, static_cast<std::size_t>(w) * 4}, {}, &why);
  const auto ca = chunks(png), cb = chunks(b);
  REQUIRE(ca[1].first == "IDAT");
  REQUIRE(cb[1].first == "IDAT");
  const std::size_t idat = 8 + 25;  // the signature, then IHDR's 13 bytes in a chunk
  const std::string spliced = png.substr(0, idat) + b.substr(idat, 12 + cb[1].second.size()) +
                              png.substr(idat + 12 + ca[1].second.size());
  { std::ofstream(d / "b.png", std::ios::binary) << spliced; }
  CHECK(whyNotSigned(d / "b.png", OutputFormat::Png) == "changed since rootsim wrote it");
  fs::remove_all(d);
}

TEST_CASE("png_encode: a picture libpng cannot write is refused with why") {
  const std::vector<unsigned char> px = pattern(4, 4, 4);
  std::string why;
  CHECK(encodeSignedPng({px.data(), 0, 4, 4, 16}, {}, &why).empty());
  CHECK(why.find("not a picture: 0x4") == 0);
  CHECK(encodeSignedPng({px.data(), 4, 4, 2, 16}, {}, &why).empty());
  CHECK(why.find("of 2 bytes") != std::string::npos);
  CHECK(encodeSignedPng({px.data(), 4, 4, 4, 8}, {}, &why).empty());
  CHECK(why.find("rows 8 bytes apart") != std::string::npos);
  // beyond libpng's size limit (its user limit: 1,000,000 pixels a side): libpng's own message
  const std::vector<unsigned char> wide(std::size_t(4) * 2000000);
  CHECK(encodeSignedPng({wide.data(), 2000000, 1, 4, wide.size()}, {}, &why).empty());
  CHECK(!why.empty());
}
