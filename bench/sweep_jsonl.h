#pragma once
// JSON Lines storage of sweep records: one JSON object per line, each line written in one
// write() and fsync'd, so that a killed sweep leaves every finished record on disk.

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace bench {

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
  std::vector<nlohmann::json> records;  ///< Every complete line that parses as an object, in order.
  std::uint64_t valid_bytes = 0;        ///< Length of the prefix that ends with the last complete line.
  std::size_t skipped_lines = 0;        ///< Lines that did not parse (a torn last line after a kill).
};

/// Reads `path`; a missing file reads as empty. Throws SweepError when it cannot be read.
JsonlContents read_jsonl(const std::string& path);

/// Cuts `path` to `bytes` (drops a torn last line before appending after it).
void truncate_file(const std::string& path, std::uint64_t bytes);

}  // namespace bench
