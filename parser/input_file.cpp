#include "parser/input_file.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace softslc {

namespace {

std::string what_it_is(mode_t m) {
  if (S_ISDIR(m)) return "a directory, not a regular file";
  if (S_ISCHR(m)) return "a character device, not a regular file";
  if (S_ISBLK(m)) return "a block device, not a regular file";
  if (S_ISFIFO(m)) return "a pipe (FIFO), not a regular file";
  if (S_ISSOCK(m)) return "a socket, not a regular file";
  return "not a regular file";
}

std::string too_big(std::size_t limit) {
  return "file larger than " + std::to_string(limit / (std::size_t{1024} * 1024)) + " MB, the limit for an input file";
}

// Closes the descriptor on every path out.
struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string normalise_text_encoding(std::string& text) {
  auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  if (text.size() >= 2 && ((byte(0) == 0xFF && byte(1) == 0xFE) || (byte(0) == 0xFE && byte(1) == 0xFF)))
    return "UTF-16 file: save it as UTF-8 (in Notepad: Save As, Encoding UTF-8)";
  // UTF-16 without a byte-order mark: ASCII text with a NUL after (or before) every character.
  if (text.size() >= 4 && ((byte(1) == 0 && byte(3) == 0 && byte(0) != 0) || (byte(0) == 0 && byte(2) == 0 && byte(1) != 0)))
    return "UTF-16 file (NUL bytes between the characters): save it as UTF-8";
  if (text.size() >= 3 && byte(0) == 0xEF && byte(1) == 0xBB && byte(2) == 0xBF) text.erase(0, 3);
  return {};
}

InputFile read_input_file(const std::filesystem::path& path, InputKind kind, std::size_t limit) {
  InputFile r;
  // O_NONBLOCK: opening a FIFO with no writer would otherwise wait forever. The type is checked
  // on the descriptor (fstat), so it is the file that is read, not one swapped in after a stat.
  Fd f{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY)};
  if (f.fd < 0) {
    r.error = std::string("cannot open file: ") + std::strerror(errno);
    return r;
  }
  struct stat st {};
  if (::fstat(f.fd, &st) != 0) {
    r.error = std::string("cannot read file: ") + std::strerror(errno);
    return r;
  }
  if (!S_ISREG(st.st_mode)) {
    r.error = what_it_is(st.st_mode);
    return r;
  }
  if (static_cast<std::uint64_t>(st.st_size) > limit) {
    r.error = too_big(limit);
    return r;
  }
  // Back to blocking reads for an ordinary file.
  if (int fl = ::fcntl(f.fd, F_GETFL); fl >= 0) ::fcntl(f.fd, F_SETFL, fl & ~O_NONBLOCK);
  r.contents.reserve(static_cast<std::size_t>(st.st_size));
  char buf[65536];
  for (;;) {
    const ssize_t n = ::read(f.fd, buf, sizeof buf);
    if (n < 0) {
      if (errno == EINTR) continue;
      r.error = std::string("cannot read file: ") + std::strerror(errno);
      r.contents.clear();
      return r;
    }
    if (n == 0) break;
    if (r.contents.size() + static_cast<std::size_t>(n) > limit) {
      r.error = too_big(limit);
      r.contents.clear();
      return r;
    }
    r.contents.append(buf, static_cast<std::size_t>(n));
  }
  if (kind == InputKind::Text) {
    r.error = normalise_text_encoding(r.contents);
    if (!r.error.empty()) {
      r.contents.clear();
      return r;
    }
  }
  r.ok = true;
  return r;
}

}  // namespace softslc
