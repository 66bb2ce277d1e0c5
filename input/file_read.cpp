#include "file_read.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace input {
namespace {

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a plain file";
}

/// Closes the descriptor on every path out.
struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string byte_text(std::uint64_t bytes) {
  char buf[48];
  if (bytes >= (std::uint64_t(1) << 30))
    std::snprintf(buf, sizeof buf, "%.1f GiB", double(bytes) / double(std::uint64_t(1) << 30));
  else if (bytes >= (std::uint64_t(1) << 20))
    std::snprintf(buf, sizeof buf, "%.1f MiB", double(bytes) / double(1 << 20));
  else if (bytes >= 1024)
    std::snprintf(buf, sizeof buf, "%.1f KiB", double(bytes) / 1024.0);
  else
    std::snprintf(buf, sizeof buf, "%llu B", static_cast<unsigned long long>(bytes));
  std::string s = buf;
  // "512.0 MiB" reads better as "512 MiB".
  if (const auto dot = s.find(".0 "); dot != std::string::npos) s.erase(dot, 2);
  return s;
}

std::string read_file(const std::string& path, std::uint64_t max_bytes, std::string_view what) {
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer forever.
  const Fd f{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY)};
  if (f.fd < 0) throw InputError(path + ": cannot open: " + std::strerror(errno));
  struct stat st {};
  if (::fstat(f.fd, &st) != 0) throw InputError(path + ": cannot stat: " + std::strerror(errno));
  if (!S_ISREG(st.st_mode))
    throw InputError(path + ": is " + kind_of(st.st_mode) + ", not a regular " + std::string(what));
  const auto limit_error = [&](std::uint64_t size, bool at_least) {
    return InputError(path + ": " + (at_least ? "more than " : "") + byte_text(size) + " is over the " +
                      byte_text(max_bytes) + " limit for " + std::string(what) + "s");
  };
  if (std::uint64_t(st.st_size) > max_bytes) throw limit_error(std::uint64_t(st.st_size), false);
  // The file is regular: clear O_NONBLOCK (it means nothing there, but keep reads plain).
  ::fcntl(f.fd, F_SETFL, ::fcntl(f.fd, F_GETFL) & ~O_NONBLOCK);

  std::string text;
  text.reserve(std::size_t(st.st_size));
  char buf[1 << 16];
  while (true) {
    const ssize_t n = ::read(f.fd, buf, sizeof buf);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw InputError(path + ": read error: " + std::strerror(errno));
    }
    if (n == 0) break;
    if (text.size() + std::size_t(n) > max_bytes) throw limit_error(max_bytes, true);
    text.append(buf, std::size_t(n));
  }
  return text;
}

}  // namespace input
