#include "valve/core/atomic_file.hpp"

#include <algorithm>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <openssl/evp.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>

#include "valve/core/error.hpp"

namespace valve {
namespace fs = std::filesystem;

namespace {
struct WrittenFiles {
  std::vector<fs::path> paths;
  bool keep = false;
};
WrittenFiles& written_files() {
  static WrittenFiles w;
  return w;
}

// A new, empty file beside `path` whose name no other process or host writing the same
// folder can take (mkstemps), so that two cluster nodes writing one shared folder never write
// into each other's temporary file. It keeps the extension, which writers go by (VTK's PLY
// writer appends ".ply" to any other name; ITK picks the image format by it), and gets the permissions an ordinary new
// file would (mkstemp's are 0600: a shared study folder would be unreadable to the group).
fs::path temp_sibling(const fs::path& path) {
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  // Every suffix from the name's first dot: ".nii.gz", ".seg.nrrd" and ".sim.vtp" all stay.
  const std::string file = path.filename().string();
  const size_t dot = file.find('.', 1);
  const std::string extension = dot == std::string::npos ? "" : file.substr(dot);
  std::string name = (dir / ("." + file.substr(0, dot) + ".tmpXXXXXX" + extension)).string();
  std::vector<char> buffer(name.begin(), name.end());
  buffer.push_back('\0');
  const int fd = ::mkstemps(buffer.data(), static_cast<int>(extension.size()));
  if (fd < 0) throw Error(path.string() + ": cannot create a temporary file beside it: " + std::strerror(errno));
  static const mode_t mode = 0666 & ~file_creation_mask();
  ::fchmod(fd, mode);
  ::close(fd);
  return fs::path(buffer.data());
}

// Flushes a file's data (or a folder's entries) to the disk, so that a crash after the rename
// leaves the whole new file, not an empty one under the final name.
void sync_to_disk(const fs::path& path, bool directory) {
  const int fd = ::open(path.c_str(), directory ? (O_RDONLY | O_DIRECTORY) : O_RDONLY);
  if (fd < 0) return;  // nothing to sync through (a folder some filesystems do not open)
  ::fsync(fd);
  ::close(fd);
}
}  // namespace

unsigned file_creation_mask() {
  // umask() can only be read by setting it, which would race with other threads creating files.
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("Umask:", 0) == 0) return static_cast<unsigned>(std::stoul(line.substr(6), nullptr, 8));
  return 022;
}

void write_via_temp(const fs::path& path, const std::function<void(const fs::path&)>& writer) {
  if (path.has_parent_path()) fs::create_directories(path.parent_path());
  const fs::path tmp = temp_sibling(path);
  try {
    writer(tmp);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
  sync_to_disk(tmp, false);
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (!ec) sync_to_disk(path.has_parent_path() ? path.parent_path() : fs::path("."), true);
  if (ec) {
    const std::string why = ec.message();  // before remove() overwrites ec
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw Error(path.string() + ": cannot move the finished file into place: " + why);
  }
  written_files().paths.push_back(path);
}

void discard_written_files() {
  WrittenFiles& w = written_files();
  if (w.keep) return;
  for (const auto& p : w.paths) {
    std::error_code ec;
    fs::remove(p, ec);
  }
  w.paths.clear();
}

void keep_written_files_on_failure() { written_files().keep = true; }

void discard_on_failure(const fs::path& path) { written_files().paths.push_back(path); }

void write_file_atomic(const fs::path& path, const std::string& content) {
  write_via_temp(path, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << content;
    out.flush();
    if (!out) throw Error(path.string() + ": cannot write the file");
  });
}

std::string read_text_file(const fs::path& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw_input_error(path.string(), "", "a readable file", "a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw_input_error(path.string(), "", "a readable file", "none");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

namespace {

std::string hex_digest(EVP_MD_CTX* ctx) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int len = 0;
  EVP_DigestFinal_ex(ctx, digest, &len);
  static const char* hex = "0123456789abcdef";
  std::string out;
  for (unsigned int i = 0; i < len; ++i) {
    out += hex[digest[i] >> 4];
    out += hex[digest[i] & 15];
  }
  return out;
}

}  // namespace

std::string sha256_file(const fs::path& path) {
  // A directory (a DICOM series) hashes as its regular files in name order: name, then bytes.
  std::vector<fs::path> files;
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    for (const auto& e : fs::directory_iterator(path))
      if (e.is_regular_file()) files.push_back(e.path());
    std::sort(files.begin(), files.end());
  } else {
    files.push_back(path);
  }
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(), EVP_MD_CTX_free);
  EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr);
  char buf[1 << 16];
  for (const fs::path& file : files) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw_input_error(file.string(), "", "a readable file", "none");
    if (files.size() > 1 || file != path) {
      const std::string name = file.filename().string();
      EVP_DigestUpdate(ctx.get(), name.data(), name.size());
    }
    while (in) {
      in.read(buf, sizeof buf);
      if (in.gcount() > 0) EVP_DigestUpdate(ctx.get(), buf, static_cast<size_t>(in.gcount()));
    }
  }
  return hex_digest(ctx.get());
}

std::string sha256_text(const std::string& text) {
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(), EVP_MD_CTX_free);
  EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr);
  EVP_DigestUpdate(ctx.get(), text.data(), text.size());
  return hex_digest(ctx.get());
}

}  // namespace valve
