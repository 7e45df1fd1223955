// ffr-reduce and its gmsh child under kill -9, the wall-clock limit of meshing, and the
// temporary files a killed writer leaves. The reference is the operating system's own account:
// /proc lists every process whose command line names the test's folder (the forked gmsh child
// has the parent's command line), and the previous output file is compared byte for byte.
#include "support.hpp"

#include "ffr/formats/sid_io.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <chrono>
#include <fstream>
#include <sstream>
#include <iterator>
#include <thread>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

using namespace ffr;
using Clock = std::chrono::steady_clock;

namespace {

const std::string kGeoBar = R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.2, 0.02, 0.012};
Physical Volume("body") = {1};
)";
// A gmsh script that never ends (1e10 passes of a loop of constant memory).
const std::string kGeoLoop = kGeoBar + R"(For i In {1:100000}
  For j In {1:100000}
    x = i + j;
  EndFor
EndFor
)";
const std::string kPart = R"({"geometry": "GEO", "mesh": {"size": 0.01MESH},
  "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}], "visual": false,
  "reduction": {"method": "free", "modes": 4}})";

std::string part_json(const std::string& geo, const std::string& mesh_extra = "") {
  std::string s = kPart;
  s.replace(s.find("GEO"), 3, geo);
  s.replace(s.find("MESH"), 4, mesh_extra);
  return s;
}

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A file under /proc/PID, or "" when the process ends while it is read: the kernel then fails
// the read with ESRCH, which std::ifstream turns into an exception.
std::string read_proc(const std::filesystem::path& p) {
  const int fd = ::open(p.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return {};
  std::string s;
  char buf[4096];
  for (ssize_t n; (n = ::read(fd, buf, sizeof buf)) != 0;) {
    if (n < 0) {
      s.clear();
      break;
    }
    s.append(buf, static_cast<size_t>(n));
  }
  ::close(fd);
  return s;
}

// Processes (not zombies) whose command line mentions `needle`: ffr-reduce and its forked child.
std::vector<pid_t> processes_naming(const std::string& needle) {
  std::vector<pid_t> found;
  for (const auto& e : std::filesystem::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    const std::string cmd = read_proc(e.path() / "cmdline");
    if (cmd.find(needle) == std::string::npos) continue;
    const std::string stat = read_proc(e.path() / "stat");
    const auto close = stat.rfind(')');
    if (close != std::string::npos && close + 2 < stat.size() && stat[close + 2] == 'Z') continue;
    found.push_back(static_cast<pid_t>(std::stol(name)));
  }
  return found;
}

// Waits up to `seconds` until no process names `needle`; returns those left.
std::vector<pid_t> wait_gone(const std::string& needle, double seconds) {
  const auto end = Clock::now() + std::chrono::duration<double>(seconds);
  std::vector<pid_t> left;
  do {
    left = processes_naming(needle);
    if (left.empty()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  } while (Clock::now() < end);
  return left;
}

// Starts ffr-reduce PART -o OUT --quiet with its output discarded; returns its process id.
pid_t start_reduce(const std::filesystem::path& part, const std::filesystem::path& out) {
  const std::string exe = test::bin("ffr-reduce").string();
  std::vector<std::string> args = {exe, part.string(), "-o", out.string(), "--quiet"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, exe.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  return rc == 0 ? pid : -1;
}

// The children of `pid` (from /proc/*/stat's parent field).
std::vector<pid_t> children_of(pid_t pid) {
  std::vector<pid_t> kids;
  for (const auto& e : std::filesystem::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    const std::string stat = read_proc(e.path() / "stat");
    const auto close = stat.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream f(stat.substr(close + 2));
    char state;
    long ppid = 0;
    if (f >> state >> ppid && ppid == pid) kids.push_back(static_cast<pid_t>(std::stol(name)));
  }
  return kids;
}

void write_previous_output(const test::TempDir& dir) {
  test::write_text(dir / "bar.geo", kGeoBar);
  test::write_text(dir / "bar.json", part_json("bar.geo"));
  const auto r = test::run(test::bin("ffr-reduce").string() + " " + (dir / "bar.json").string() + " -o " +
                           (dir / "out.sid.h5").string() + " --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
}

}  // namespace

// The issue's case: kill -9 of ffr-reduce while its gmsh child runs a script that loops. Before
// PR_SET_PDEATHSIG the child was reparented to init and kept looping.
TEST(ReduceChild, KillNineWhileMeshingLeavesNoChildAndTheOldOutput) {
  test::TempDir dir("kill-mesh");
  write_previous_output(dir);
  const std::string before = slurp(dir / "out.sid.h5");
  ASSERT_FALSE(before.empty());
  test::write_text(dir / "loop.geo", kGeoLoop);
  test::write_text(dir / "loop.json", part_json("loop.geo"));

  const pid_t pid = start_reduce(dir / "loop.json", dir / "out.sid.h5");
  ASSERT_GT(pid, 0);
  // Wait for the gmsh child, then give it time to be inside the loop.
  std::vector<pid_t> kids;
  for (auto end = Clock::now() + std::chrono::seconds(60); kids.empty() && Clock::now() < end;) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    kids = children_of(pid);
  }
  ASSERT_FALSE(kids.empty()) << "ffr-reduce started no gmsh process";
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  EXPECT_EQ(processes_naming(dir.path().string()).size(), 2u) << "ffr-reduce and its child run";

  ASSERT_EQ(::kill(pid, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
  const auto left = wait_gone(dir.path().string(), 5.0);
  EXPECT_TRUE(left.empty()) << left.size() << " process(es) left, first " << (left.empty() ? 0 : left[0]);
  for (pid_t k : left) ::kill(k, SIGKILL);  // not to leave them to the machine when the test fails
  EXPECT_EQ(slurp(dir / "out.sid.h5"), before) << "the previous output changed";
}

TEST(ReduceChild, MeshingPastTheTimeLimitIsStoppedAndRefused) {
  test::TempDir dir("mesh-limit");
  test::write_text(dir / "loop.geo", kGeoLoop);
  test::write_text(dir / "part.json", part_json("loop.geo", R"(, "time_limit_s": 1.5)"));
  const auto t0 = Clock::now();
  const auto r = test::run(test::bin("ffr-reduce").string() + " " + (dir / "part.json").string() + " -o " +
                           (dir / "out.sid.h5").string() + " --quiet");
  const double took = std::chrono::duration<double>(Clock::now() - t0).count();
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("loop.geo"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("within 1.5 s"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("mesh.time_limit_s of part.json"), std::string::npos) << r.output;
  EXPECT_LT(took, 30.0) << "the limit did not stop it in time";
  EXPECT_GE(took, 1.5);
  EXPECT_FALSE(std::filesystem::exists(dir / "out.sid.h5"));
  EXPECT_TRUE(wait_gone(dir.path().string(), 2.0).empty()) << "gmsh still runs";
}

// kill -9 at every moment of a whole run (from start to the rename of the output): the output
// is always either the previous file, byte for byte, or a complete new one that reads; no
// process is left; the next run removes any temporary file a kill left and writes its output.
TEST(ReduceChild, KillNineAtAnyMomentKeepsTheOutputWhole) {
  test::TempDir dir("kill-any");
  write_previous_output(dir);
  const std::string before = slurp(dir / "out.sid.h5");
  // How long a run takes here, to spread the kills over it.
  const auto t0 = Clock::now();
  write_previous_output(dir);
  const double run_s = std::chrono::duration<double>(Clock::now() - t0).count();
  const std::string mine = slurp(dir / "out.sid.h5");  // the same run twice: the same bytes
  ASSERT_EQ(mine.size(), before.size());
  int killed = 0, finished = 0, temporaries = 0;
  const int tries = 16;
  for (int k = 0; k < tries; ++k) {
    const pid_t pid = start_reduce(dir / "bar.json", dir / "out.sid.h5");
    ASSERT_GT(pid, 0);
    std::this_thread::sleep_for(std::chrono::duration<double>(run_s * (0.1 + 1.3 * k / tries)));
    ::kill(pid, SIGKILL);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    (WIFSIGNALED(status) ? killed : finished) += 1;
    EXPECT_TRUE(wait_gone(dir.path().string(), 5.0).empty()) << "a process outlived kill " << k;
    ASSERT_NO_THROW(formats::read_sid(dir / "out.sid.h5")) << "after kill " << k;
    for (const auto& f : std::filesystem::directory_iterator(dir.path()))
      temporaries += f.path().filename().string().find(".tmp-") != std::string::npos ? 1 : 0;
  }
  EXPECT_GT(killed, 0);
  // One more complete run: no temporary file is left next to its output.
  write_previous_output(dir);
  for (const auto& f : std::filesystem::directory_iterator(dir.path()))
    EXPECT_EQ(f.path().filename().string().find(".tmp-"), std::string::npos) << "left: " << f.path();
  std::printf("kill -9 at %d moments: %d killed, %d had finished; a temporary file seen after %d kills\n", tries, killed,
              finished, temporaries);
}

// Temporary files of writers that were killed are removed by the next writer of the same
// target; those of a live process, of another host or of another target stay.
TEST(ReduceChild, StaleTemporaryFilesAreRemovedByTheNextRun) {
  test::TempDir dir("stale");
  // A process id that is not alive: a child that has ended and been reaped.
  const pid_t dead = [] {
    const pid_t p = ::fork();
    if (p == 0) ::_exit(0);
    int st = 0;
    ::waitpid(p, &st, 0);
    return p;
  }();
  ASSERT_NE(::kill(dead, 0), 0);
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  std::string h;
  for (const char* c = host; *c && h.size() < 64; ++c) h += (std::isalnum(static_cast<unsigned char>(*c)) || *c == '.' || *c == '_') ? *c : '_';
  const std::string d = std::to_string(dead), me = std::to_string(::getpid());
  const std::vector<std::string> stale = {".out.sid.h5.tmp-" + d + "-1a2b",                  // the name before hosts
                                          ".out.sid.h5.tmp-" + h + "-" + d + "-3c4d"};       // this host, dead
  const std::vector<std::string> kept = {".out.sid.h5.tmp-" + h + "-" + me + "-5e6f",        // a live writer
                                         ".out.sid.h5.tmp-other_host-" + d + "-7a8b",        // another host
                                         ".other.sid.h5.tmp-" + h + "-" + d + "-9c0d"};      // another target
  for (const auto& n : stale) test::write_text(dir / n, "partial");
  for (const auto& n : kept) test::write_text(dir / n, "partial");
  write_previous_output(dir);
  for (const auto& n : stale) EXPECT_FALSE(std::filesystem::exists(dir / n)) << n;
  for (const auto& n : kept) EXPECT_TRUE(std::filesystem::exists(dir / n)) << n;
  EXPECT_NO_THROW(formats::read_sid(dir / "out.sid.h5"));

  // A live process id that was reused: the process started after the file's last write.
  const std::string reused = ".out.sid.h5.tmp-" + h + "-1-aaaa";  // init, started at boot
  test::write_text(dir / reused, "partial");
  std::filesystem::last_write_time(dir / reused, std::filesystem::file_time_type::clock::now() - std::chrono::hours(24 * 365 * 30));
  write_previous_output(dir);
  EXPECT_FALSE(std::filesystem::exists(dir / reused)) << "a file older than its writer's process";
}

// kill -9 at the moment of writing: the temporary file is watched for and the run killed as soon
// as it appears. The previous output stays byte for byte, the temporary file is left (what the
// issue found accumulating), and the next run removes it.
TEST(ReduceChild, KillNineWhileWritingLeavesTheOldOutputAndTheNextRunCleansUp) {
  test::TempDir dir("kill-write");
  write_previous_output(dir);
  std::string before = slurp(dir / "out.sid.h5");
  const auto temporary = [&] {
    for (const auto& f : std::filesystem::directory_iterator(dir.path()))
      if (f.path().filename().string().find(".tmp-") != std::string::npos) return f.path();
    return std::filesystem::path();
  };
  bool caught = false;
  for (int attempt = 0; attempt < 5 && !caught; ++attempt) {
    const pid_t pid = start_reduce(dir / "bar.json", dir / "out.sid.h5");
    ASSERT_GT(pid, 0);
    int status = 0;
    for (;;) {
      if (!temporary().empty()) {
        ::kill(pid, SIGKILL);
        caught = true;
        break;
      }
      if (::waitpid(pid, &status, WNOHANG) == pid) break;  // finished before it was seen: again
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    if (caught) ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    if (caught && !WIFSIGNALED(status)) caught = false;  // it had finished meanwhile
    if (!caught) before = slurp(dir / "out.sid.h5");     // a finished run: its output is the previous one
  }
  ASSERT_TRUE(caught) << "the write moment was never caught in 5 runs";
  EXPECT_TRUE(wait_gone(dir.path().string(), 5.0).empty());
  EXPECT_EQ(slurp(dir / "out.sid.h5"), before) << "the previous output changed";
  const auto left = temporary();
  EXPECT_FALSE(left.empty()) << "no temporary file after a kill while writing";
  write_previous_output(dir);
  EXPECT_TRUE(temporary().empty()) << "the next run left " << temporary();
  EXPECT_EQ(slurp(dir / "out.sid.h5").size(), before.size());
}
