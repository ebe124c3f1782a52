#pragma once
// Reads back what core/vtu_writer.hpp writes, for the tests: the file's text and a DataArray's inline
// base64 payload. Independent of the writer's encoder on purpose, so a shared bug cannot cancel out.
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace terracal::test {

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline std::vector<unsigned char> base64_decode(const std::string& s) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  std::vector<unsigned char> out;
  std::uint32_t acc = 0;
  int bits = 0;
  for (const char c : s) {
    const int v = value(c);
    if (v < 0) continue;  // whitespace and '=' padding
    acc = (acc << 6) | static_cast<std::uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<unsigned char>((acc >> bits) & 0xFF));
    }
  }
  return out;
}

// The payload of the DataArray called `name`: checks the UInt32 byte-count header against the
// decoded length and returns the data as T.
template <class T>
std::vector<T> array_payload(const std::string& xml, const std::string& name) {
  const auto at = xml.find("Name=\"" + name + "\"");
  REQUIRE(at != std::string::npos);
  const auto begin = xml.find('>', at) + 1;
  const auto end = xml.find('<', begin);
  const std::vector<unsigned char> bytes = base64_decode(xml.substr(begin, end - begin));
  REQUIRE(bytes.size() >= 4);
  std::uint32_t header = 0;
  std::memcpy(&header, bytes.data(), 4);
  REQUIRE(header == bytes.size() - 4);
  REQUIRE(header % sizeof(T) == 0);
  std::vector<T> values(header / sizeof(T));
  if (header > 0) std::memcpy(values.data(), bytes.data() + 4, header);
  return values;
}

}  // namespace terracal::test
