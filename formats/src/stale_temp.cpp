#include "ffr/formats/stale_temp.hpp"

#include <cerrno>
#include <charconv>
#include <fstream>
#include <sstream>
#include <string_view>
#include <system_error>

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

namespace ffr::formats::h5::detail {
namespace {

// This host's name with only [A-Za-z0-9._] kept (others become '_'), at most 64 characters.
std::string host_tag() {
  char buf[256] = {};
  if (::gethostname(buf, sizeof buf - 1) != 0 || !buf[0]) return "host";
  std::string h;
  for (const char* c = buf; *c && h.size() < 64; ++c) {
    const bool ok = (*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') || *c == '.' || *c == '_';
    h += ok ? *c : '_';
  }
  return h;
}

bool all_of(std::string_view s, bool (*pred)(char)) {
  if (s.empty()) return false;
  for (char c : s)
    if (!pred(c)) return false;
  return true;
}
bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_hex(char c) { return is_digit(c) || (c >= 'a' && c <= 'f'); }

// When process `pid` started, in seconds since the epoch; negative if unknown. From
// /proc/PID/stat (field 22, clock ticks after boot) and /proc/stat's btime.
double process_start(long pid) {
  // getline, not an istreambuf_iterator: if the process ends during the read, the kernel fails
  // it with ESRCH, which the stream's own functions turn into a failed read, not an exception.
  std::ifstream st("/proc/" + std::to_string(pid) + "/stat");
  std::string text;
  std::getline(st, text);
  const auto close = text.rfind(')');  // the command name may hold spaces and parentheses
  if (close == std::string::npos) return -1;
  std::istringstream fields(text.substr(close + 1));
  std::string f;
  unsigned long long ticks = 0;
  for (int i = 3; i <= 22 && fields >> f; ++i)
    if (i == 22) std::from_chars(f.data(), f.data() + f.size(), ticks);
  if (!ticks) return -1;
  std::ifstream ps("/proc/stat");
  std::string key;
  double btime = -1;
  while (ps >> key)
    if (key == "btime") {
      ps >> btime;
      break;
    }
  const long hz = ::sysconf(_SC_CLK_TCK);
  if (btime < 0 || hz <= 0) return -1;
  return btime + static_cast<double>(ticks) / static_cast<double>(hz);
}

}  // namespace

std::filesystem::path temporary_name(const std::filesystem::path& target, unsigned long long random) {
  std::ostringstream o;
  o << '.' << target.filename().string() << ".tmp-" << host_tag() << '-' << ::getpid() << '-' << std::hex << random;
  return target.parent_path() / o.str();
}

bool is_stale_temporary(const std::string& target_filename, const std::string& name, double mtime_s) {
  const std::string prefix = "." + target_filename + ".tmp-";
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return false;
  std::string_view rest(name);
  rest.remove_prefix(prefix.size());
  // HOST-PID-HEX, or PID-HEX as written before the host was part of the name (taken as this host's).
  const auto last = rest.rfind('-');
  if (last == std::string_view::npos) return false;
  const std::string_view hex = rest.substr(last + 1);
  std::string_view head = rest.substr(0, last);
  const auto mid = head.rfind('-');
  const std::string_view pid_text = mid == std::string_view::npos ? head : head.substr(mid + 1);
  if (mid != std::string_view::npos && head.substr(0, mid) != host_tag()) return false;
  if (!all_of(hex, is_hex) || !all_of(pid_text, is_digit) || pid_text.size() > 9) return false;
  long pid = 0;
  std::from_chars(pid_text.data(), pid_text.data() + pid_text.size(), pid);
  if (pid <= 0) return false;
  if (pid == ::getpid()) return false;  // this process's own writer (another AtomicFile still open)
  if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) return true;
  // The id is in use: by the writer, or by a process that started after the writer's last
  // write (the id was reused). Two seconds of margin for btime's whole seconds.
  const double started = process_start(pid);
  return started > 0 && started > mtime_s + 2.0;
}

namespace {

int remove_stale(const std::filesystem::path& target, bool folders) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  const std::string file = target.filename().string();
  const std::string prefix = "." + file + ".tmp-";
  int removed = 0;
  fs::directory_iterator it(dir, ec), end;
  for (; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    struct stat sb;
    if (::lstat(it->path().c_str(), &sb) != 0 || !(folders ? S_ISDIR(sb.st_mode) : S_ISREG(sb.st_mode))) continue;
    const double mtime = static_cast<double>(sb.st_mtim.tv_sec) + 1e-9 * static_cast<double>(sb.st_mtim.tv_nsec);
    if (!is_stale_temporary(file, name, mtime)) continue;
    std::error_code rm;
    if (folders ? fs::remove_all(it->path(), rm) > 0 : fs::remove(it->path(), rm)) ++removed;
  }
  return removed;
}

}  // namespace

int remove_stale_temporaries(const std::filesystem::path& target) { return remove_stale(target, false); }

int remove_stale_temporary_folders(const std::filesystem::path& target) { return remove_stale(target, true); }

}  // namespace ffr::formats::h5::detail
