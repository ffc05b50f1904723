#pragma once
// PNG files (lossless, 8-bit RGBA) for single frames and figure panels.
#include <string>

#include "rootsim/image.hpp"

namespace rootsim {

// write img to path atomically (a temporary file beside it, then rename); fast zlib settings
// (compression level 1, "sub" filter; their cost: docs/rendering.md, "Speed").
// Throws RenderError naming the path and the system error on failure.
void writePng(const std::string& path, const Image& img);

// read a PNG file into an RGBA image (any channel count is expanded to RGBA); throws RenderError
Image readPng(const std::string& path);

}  // namespace rootsim
