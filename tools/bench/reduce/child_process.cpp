#include "child_process.hpp"

#include <chrono>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <signal.h>
#include <sstream>
#include <stdexcept>
#include <sys/resource.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace ffr::bench {
namespace {

// Resident set of a running process in KiB (VmRSS), 0 once it is gone.
std::int64_t current_rss_kib(pid_t pid) {
  std::ifstream f("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::strtoll(line.c_str() + 6, nullptr, 10);
  return 0;
}

double seconds(const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); }

// In the child after fork: only async-signal-safe calls until exec.
[[noreturn]] void exec_child(const ChildSpec& spec, char* const* argv) {
  ::setpgid(0, 0);  // own process group, so a cap kills every thread and helper
  if (!spec.cwd.empty() && ::chdir(spec.cwd.c_str()) != 0) ::_exit(126);
  for (const auto& [k, v] : spec.env) ::setenv(k.c_str(), v.c_str(), 1);
  auto redirect = [](const std::filesystem::path& p, int fd) {
    if (p.empty()) return;
    const int f = ::open(p.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (f < 0 || ::dup2(f, fd) < 0) ::_exit(126);
    ::close(f);
  };
  redirect(spec.out, STDOUT_FILENO);
  redirect(spec.err, STDERR_FILENO);
  ::execvp(argv[0], argv);
  ::_exit(127);
}

}  // namespace

double load_average() {
  std::ifstream f("/proc/loadavg");
  double l = 0;
  f >> l;
  return l;
}

std::int64_t mem_available_kib() {
  std::ifstream f("/proc/meminfo");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("MemAvailable:", 0) == 0) return std::strtoll(line.c_str() + 13, nullptr, 10);
  return 0;
}

double wait_for_quiet(double below, double max_wait_s, bool verbose) {
  const auto t0 = std::chrono::steady_clock::now();
  double l = load_average();
  bool said = false;
  while (below > 0 && l >= below &&
         std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < max_wait_s) {
    if (verbose && !said) std::fprintf(stderr, "  waiting for load average < %.1f (now %.2f)\n", below, l);
    said = true;
    std::this_thread::sleep_for(std::chrono::seconds(15));
    l = load_average();
  }
  return l;
}

ChildResult run_child(const ChildSpec& spec) {
  if (spec.argv.empty()) throw std::invalid_argument("run_child: empty argv");
  std::vector<std::string> args = spec.argv;
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  ChildResult r;
  r.load_before = load_average();
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) exec_child(spec, argv.data());
  ::setpgid(pid, pid);  // also here: no race with the child's own call

  int status = 0;
  rusage ru{};
  for (;;) {
    const pid_t w = ::wait4(pid, &status, WNOHANG, &ru);
    if (w == pid) break;
    if (w < 0 && errno != EINTR) throw std::runtime_error(std::string("wait4: ") + std::strerror(errno));
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const bool over_time = spec.timeout_s > 0 && t > spec.timeout_s;
    const bool over_mem = spec.max_rss_kib > 0 && current_rss_kib(pid) > spec.max_rss_kib;
    if (over_time || over_mem) {
      r.timed_out = over_time;
      r.memory_capped = over_mem && !over_time;
      ::kill(-pid, SIGKILL);
      ::wait4(pid, &status, 0, &ru);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.user_s = seconds(ru.ru_utime);
  r.sys_s = seconds(ru.ru_stime);
  r.peak_rss_kib = ru.ru_maxrss;
  if (WIFEXITED(status)) r.exit_status = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
  r.load_after = load_average();
  return r;
}

}  // namespace ffr::bench
