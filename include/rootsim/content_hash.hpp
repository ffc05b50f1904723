#pragma once
// SHA-256 of bytes and files through OpenSSL's libcrypto (EVP): the content hash of the markers that
// record what rootsim wrote (write_rule.hpp) and of the signatures inside single files (PNG, RSML,
// GLB, MP4). Header only: the renderer signs its files without linking rootsim_io (it links libcrypto).
#include <openssl/evp.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>

namespace rootsim {

// SHA-256 fed in pieces: update() as often as needed, then hex() once
class Sha256 {
 public:
  Sha256() : ctx_(EVP_MD_CTX_new(), EVP_MD_CTX_free) {
    if (!ctx_ || EVP_DigestInit_ex(ctx_.get(), EVP_sha256(), nullptr) != 1) ctx_.reset();
  }
  void update(const void* data, std::size_t n) {
    if (ctx_ && n > 0 && EVP_DigestUpdate(ctx_.get(), data, n) != 1) ctx_.reset();
  }
  void update(std::string_view s) { update(s.data(), s.size()); }
  // 64 lower-case hex digits; "" when libcrypto failed (never taken as a match)
  std::string hex() {
    unsigned char md[EVP_MAX_MD_SIZE];
    unsigned int n = 0;
    if (!ctx_ || EVP_DigestFinal_ex(ctx_.get(), md, &n) != 1) return "";
    ctx_.reset();
    static const char* digits = "0123456789abcdef";
    std::string s;
    for (unsigned int i = 0; i < n; ++i) {
      s += digits[md[i] >> 4];
      s += digits[md[i] & 15];
    }
    return s;
  }

 private:
  std::unique_ptr<EVP_MD_CTX, void (*)(EVP_MD_CTX*)> ctx_;
};

inline std::string sha256Hex(std::string_view bytes) {
  Sha256 h;
  h.update(bytes);
  return h.hex();
}

// the file's SHA-256 streamed in blocks, and its size; "" when it cannot be read
inline std::string sha256File(const std::filesystem::path& file, std::uintmax_t* size = nullptr) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return "";
  Sha256 h;
  std::string buf(1 << 16, '\0');
  std::uintmax_t total = 0;
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    const auto got = static_cast<std::size_t>(in.gcount());
    h.update(buf.data(), got);
    total += got;
  }
  if (in.bad()) return "";
  if (size) *size = total;
  return h.hex();
}

}  // namespace rootsim
