#pragma once
// JSON Lines storage of sweep records: one JSON object per line, each line written in one
// write() and fsync'd, so that a killed sweep leaves every finished record on disk.

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace harness {

/// Appends records to a JSON Lines file.
class JsonlWriter {
 public:
  /// Opens `path` for appending, creating it; `truncate` starts it afresh. Throws SweepError.
  JsonlWriter(const std::string& path, bool truncate);
  ~JsonlWriter();
  JsonlWriter(const JsonlWriter&) = delete;
  JsonlWriter& operator=(const JsonlWriter&) = delete;

  /// Writes `record` as one line and fsyncs the file. Throws SweepError on an I/O error.
  void append(const nlohmann::json& record);

  /// The file written to.
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
};

/// What a JSON Lines file holds.
struct JsonlContents {
  std::vector<nlohmann::json> records;  ///< Every complete line, each a JSON object, in order.
  std::vector<std::size_t> lines;       ///< The line number (1-based) of each record.
  std::uint64_t valid_bytes = 0;        ///< Length of the prefix that ends with the last complete line.
  bool torn_tail = false;               ///< Text after the last newline (a write cut by a kill) was dropped.
};

/// Parses JSON Lines text strictly: every complete line (one that ends in a newline) must be a
/// JSON object (input::parse_json: nesting limit, no duplicate keys); blank lines are skipped.
/// Only text after the last newline, a line torn by a kill mid-write, is dropped. Throws
/// SweepError "<name>:<line>: <what is wrong>".
JsonlContents parse_jsonl(std::string_view text, const std::string& name);

/// Reads `path` (a regular file within input::kMaxResultsFileBytes) and parses it; a missing
/// file reads as empty. Throws SweepError naming the path.
JsonlContents read_jsonl(const std::string& path);

/// Cuts `path` to `bytes` (drops a torn last line before appending after it).
void truncate_file(const std::string& path, std::uint64_t bytes);

}  // namespace harness
