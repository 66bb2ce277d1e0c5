#include "harness/sweep_jsonl.h"

#include "harness/sweep_definition.h"

#include "input/file_read.h"
#include "input/json_read.h"
#include "input/message.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace harness {

JsonlWriter::JsonlWriter(const std::string& path, bool truncate) : path_(path) {
  const auto parent = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  // O_NONBLOCK: a FIFO without a reader fails at once instead of blocking; only regular files
  // are written (a JSON Lines file is read back by --resume).
  fd_ = ::open(path.c_str(),
               O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC | O_NONBLOCK | O_NOCTTY | (truncate ? O_TRUNC : 0), 0644);
  if (fd_ < 0) throw SweepError(path + ": cannot open for writing: " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    fd_ = -1;
    throw SweepError(path + ": not a regular file; cannot write JSON Lines there");
  }
  ::fcntl(fd_, F_SETFL, ::fcntl(fd_, F_GETFL) & ~O_NONBLOCK);
}

JsonlWriter::~JsonlWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void JsonlWriter::append(const nlohmann::json& record) {
  // Invalid UTF-8 (a scene name from a file name) is replaced, never thrown.
  const std::string line = record.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
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

JsonlContents parse_jsonl(std::string_view text, const std::string& name) {
  JsonlContents out;
  std::size_t start = 0, line = 0;
  while (start < text.size()) {
    const std::size_t nl = text.find('\n', start);
    if (nl == std::string_view::npos) {  // no newline: a line torn by a kill mid-write
      out.torn_tail = true;
      break;
    }
    ++line;
    const std::string_view text_line = text.substr(start, nl - start);
    start = nl + 1;
    out.valid_bytes = start;
    if (text_line.find_first_not_of(" \t\r") == std::string_view::npos) continue;
    nlohmann::json j;
    try {
      j = input::parse_json(text_line);
    } catch (const input::InputError& e) {
      throw SweepError(name + ":" + std::to_string(line) + ": " + e.what());
    }
    if (!j.is_object())
      throw SweepError(name + ":" + std::to_string(line) + ": (root): must be a JSON object, got " + input::brief(j));
    out.records.push_back(std::move(j));
    out.lines.push_back(line);
  }
  return out;
}

JsonlContents read_jsonl(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec) && !std::filesystem::is_symlink(path, ec)) return {};
  return parse_jsonl(read_input_file(path, input::kMaxResultsFileBytes, "JSON Lines file"), path);
}

void truncate_file(const std::string& path, std::uint64_t bytes) {
  std::error_code ec;
  std::filesystem::resize_file(path, bytes, ec);
  if (ec) throw SweepError(path + ": cannot truncate: " + ec.message());
}

}  // namespace harness
