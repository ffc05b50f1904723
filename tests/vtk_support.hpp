#pragma once
// reading rootsim's ParaView files in the tests (docs/outputs.md, ParaView files): the zlib-compressed
// appended arrays, decoded with zlib as the format describes them
#include <doctest/doctest.h>
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace rootsim::test {

// the appended data of a VTK XML file written with vtkZLibDataCompressor and header_type UInt64: the
// array at `offset`, decompressed
inline std::string vtkArray(const std::string& file, std::size_t offset) {
  const std::size_t start = file.find("<AppendedData encoding=\"raw\">\n_");
  REQUIRE(start != std::string::npos);
  const char* p = file.data() + start + std::strlen("<AppendedData encoding=\"raw\">\n_") + offset;
  std::uint64_t head[3];
  std::memcpy(head, p, sizeof head);
  const std::uint64_t blocks = head[0], blockSize = head[1], last = head[2];
  std::vector<std::uint64_t> sizes(blocks);
  std::memcpy(sizes.data(), p + sizeof head, blocks * 8);
  const char* data = p + sizeof head + blocks * 8;
  std::string out;
  for (std::uint64_t k = 0; k < blocks; ++k) {
    uLongf n = (k + 1 == blocks && last != 0) ? last : blockSize;
    std::string block(n, '\0');
    REQUIRE(uncompress(reinterpret_cast<Bytef*>(block.data()), &n, reinterpret_cast<const Bytef*>(data), sizes[k]) == Z_OK);
    block.resize(n);
    out += block;
    data += sizes[k];
  }
  return out;
}

// the offset= of the DataArray named `name` (Points: the first, unnamed), the first after `section`
// ("<PointData", "<CellData", "<Lines", "<Polys"; "": the first in the file)
inline std::size_t vtkOffset(const std::string& file, const std::string& name, const std::string& section = "") {
  const std::size_t from = section.empty() ? 0 : file.find(section);
  REQUIRE(from != std::string::npos);
  const std::size_t at = name.empty() ? file.find("<Points>", from) : file.find("Name=\"" + name + "\"", from);
  REQUIRE(at != std::string::npos);
  const std::size_t o = file.find("offset=\"", at) + 8;
  return std::stoul(file.substr(o, file.find('"', o) - o));
}

template <class T>
std::vector<T> as(const std::string& bytes) {
  std::vector<T> v(bytes.size() / sizeof(T));
  std::memcpy(v.data(), bytes.data(), v.size() * sizeof(T));
  return v;
}
}  // namespace rootsim::test
