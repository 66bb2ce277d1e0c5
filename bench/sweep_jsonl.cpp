#include "sweep_jsonl.h"

#include "sweep_definition.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace bench {

JsonlWriter::JsonlWriter(const std::string& path, bool truncate) : path_(path) {
  const auto parent = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC | (truncate ? O_TRUNC : 0), 0644);
  if (fd_ < 0) throw SweepError(path + ": cannot open for writing: " + std::strerror(errno));
}

JsonlWriter::~JsonlWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void JsonlWriter::append(const nlohmann::json& record) {
  const std::string line = record.dump() + "\n";
  std::size_t done = 0;
  while (done < line.size()) {
    const ssize_t n = ::write(fd_, line.data() + done, line.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw SweepError(path_ + ": write failed: " + std::strerror(errno));
    }
    done += std::size_t(n);
  }
  if (::fsync(fd_) != 0) throw SweepError(path_ + ": fsync failed: " + std::strerror(errno));
}

JsonlContents read_jsonl(const std::string& path) {
  JsonlContents out;
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return out;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SweepError(path + ": cannot open for reading");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t nl = text.find('\n', start);
    if (nl == std::string::npos) {  // no newline: a line torn by a kill mid-write
      out.skipped_lines++;
      break;
    }
    const std::string_view line(text.data() + start, nl - start);
    start = nl + 1;
    out.valid_bytes = start;
    if (line.empty()) continue;
    try {
      auto j = nlohmann::json::parse(line);
      if (j.is_object()) {
        out.records.push_back(std::move(j));
        continue;
      }
    } catch (const nlohmann::json::parse_error&) {
    }
    out.skipped_lines++;
  }
  return out;
}

void truncate_file(const std::string& path, std::uint64_t bytes) {
  std::error_code ec;
  std::filesystem::resize_file(path, bytes, ec);
  if (ec) throw SweepError(path + ": cannot truncate: " + ec.message());
}

}  // namespace bench
