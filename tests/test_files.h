#pragma once
// Reading a file whole, for the tests that check what a script or command wrote.

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace test_files {

/// The bytes of `path`, or "" when it cannot be opened.
inline std::string read(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace test_files
