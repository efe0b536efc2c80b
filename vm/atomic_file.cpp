#include "vm/atomic_file.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace softslc {

std::string write_file_atomically(const std::filesystem::path& link_or_path, std::string_view contents) {
  // A symbolic link is written through: the file it names is replaced and the link stays (a
  // rename over the link would replace the link by a regular file). A dangling link is refused.
  std::filesystem::path path = link_or_path;
  struct stat lst {};
  if (::lstat(path.c_str(), &lst) == 0 && S_ISLNK(lst.st_mode)) {
    std::error_code ec;
    path = std::filesystem::canonical(link_or_path, ec);
    if (ec) return link_or_path.string() + ": a symbolic link to a file that does not exist (" + ec.message() + ")";
  }
  // Only a regular file is replaced: renaming over /dev/null or a FIFO would replace the device.
  struct stat existing {};
  const bool exists = ::stat(path.c_str(), &existing) == 0;
  if (exists && !S_ISREG(existing.st_mode)) return path.string() + ": not a regular file; refusing to replace it";
  auto dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  std::string tmpl = (dir / ("." + path.filename().string() + ".XXXXXX")).string();
  int fd = ::mkstemp(tmpl.data());
  if (fd < 0) return "cannot create a temporary file in " + dir.string() + ": " + std::strerror(errno);
  auto fail = [&](const char* what) {
    std::string msg = std::string(what) + " " + tmpl + ": " + std::strerror(errno);
    ::close(fd);
    ::unlink(tmpl.c_str());
    return msg;
  };
  std::size_t done = 0;
  while (done < contents.size()) {
    ssize_t n = ::write(fd, contents.data() + done, contents.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return fail("cannot write");
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) return fail("cannot flush");
  // A replaced file keeps its permissions (a 0600 state file stays private); a new one gets what
  // the umask gives a new file, not mkstemp's 0600.
  if (exists) {
    ::fchmod(fd, existing.st_mode & 07777);
  } else {
    mode_t mask = ::umask(0);
    ::umask(mask);
    ::fchmod(fd, 0666 & ~mask);
  }
  if (::close(fd) != 0) {
    ::unlink(tmpl.c_str());
    return "cannot close " + tmpl + ": " + std::strerror(errno);
  }
  if (::rename(tmpl.c_str(), path.c_str()) != 0) {
    std::string msg = "cannot replace " + path.string() + ": " + std::strerror(errno);
    ::unlink(tmpl.c_str());
    return msg;
  }
  // Make the rename itself durable.
  int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
  return {};
}

}  // namespace softslc
