// bin/ffr-reduce is a launcher (preproc/launcher): it chooses the page size of the reduction's
// heap and starts libexec/ffr/ffr-reduce-main. The choice must change the page faults, never
// the result; the user's setting and glibc tunables stand; a broken installation is an error
// that names the missing program. gmsh's module (preproc/src/mesh/gmsh_module.hpp) is loaded
// only for a part that needs gmsh: without it the program starts and reads an MSH 4.1 file,
// and a geometry to mesh is refused naming the module, unless FFR_GMSH_MODULE points at it.
#include "ffr/formats/text_file.hpp"
#include "huge_page_verdict.h"
#include "support.hpp"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <fstream>
#include <sstream>
#include <vector>

extern char** environ;

using namespace ffr;

namespace {

// A clamped bar of ~6 000 DOF (TET10): large enough for its heap to take a few thousand faults.
void write_bar(const test::TempDir& dir) {
  test::write_text(dir / "bar.geo", R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.3, 0.03, 0.02};
Physical Volume("body") = {1};
Physical Surface("clamp") = Surface In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};
)");
  test::write_text(dir / "part.json", R"({"geometry": "bar.geo", "mesh": {"size": 0.008, "order": 2},
    "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}],
    "interfaces": [{"name": "root", "group": "clamp", "coupling": "rigid"}],
    "reduction": {"method": "clamped", "interface": "root", "modes": 6}})");
}

struct Launched {
  int status = -1;
  long minor_faults = 0;  ///< of the reduction program (the launcher replaced itself with it)
  std::string log;
};

// Runs `env ... ffr-reduce part.json -o out` with wait4, for the child's page faults.
Launched launch(const test::TempDir& dir, const std::vector<std::string>& env, const std::string& out) {
  const std::string log_path = (dir / (out + ".log")).string();
  std::vector<std::string> args{"/usr/bin/env"};
  args.insert(args.end(), env.begin(), env.end());
  for (const std::string& a : {test::bin("ffr-reduce").string(), (dir / "part.json").string(), std::string("-o"),
                               (dir / out).string(), std::string("--threads"), std::string("1")})
    args.push_back(a);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 2, log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  Launched r;
  if (posix_spawn(&pid, argv[0], &files, nullptr, argv.data(), environ) != 0) return r;
  posix_spawn_file_actions_destroy(&files);
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.minor_faults = usage.ru_minflt;
  std::ifstream in(log_path);
  std::stringstream s;
  s << in.rdbuf();
  r.log = s.str();
  return r;
}

bool transparent_huge_pages() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  return std::getline(in, line) && line.find("[never]") == std::string::npos;
}

}  // namespace

TEST(Launcher, HeapPagesFollowTheSettingAndTheResultDoesNot) {
  test::TempDir dir("pages");
  write_bar(dir);
  const Launched off = launch(dir, {"-u", "GLIBC_TUNABLES", "FFR_HUGE_PAGES=off"}, "off.sid.h5");
  const Launched on = launch(dir, {"-u", "GLIBC_TUNABLES", "FFR_HUGE_PAGES=on"}, "on.sid.h5");
  ASSERT_EQ(off.status, 0) << off.log;
  ASSERT_EQ(on.status, 0) << on.log;
  EXPECT_NE(off.log.find("memory: 2 MiB heap pages off"), std::string::npos) << off.log;
  EXPECT_NE(on.log.find("memory: 2 MiB heap pages on"), std::string::npos) << on.log;
  // The page size moves no bit of the result.
  const auto diff = test::run(test::bin("ffr-diff").string() + " " + (dir / "off.sid.h5").string() + " " +
                              (dir / "on.sid.h5").string() + " --rtol 0 --atol 0");
  EXPECT_EQ(diff.status, 0) << diff.output;
  // And the setting takes: with 2 MiB pages the heap faults in a small fraction of the pages.
  if (!transparent_huge_pages()) GTEST_SKIP() << "transparent huge pages are off on this machine";
  EXPECT_LT(on.minor_faults, off.minor_faults / 2) << "faults with 2 MiB pages " << on.minor_faults << ", with 4 KiB "
                                                    << off.minor_faults;
}

TEST(Launcher, AutomaticChoiceIsMeasuredAndLogged) {
  test::TempDir dir("auto");
  write_bar(dir);
  const Launched r = launch(dir, {"-u", "FFR_HUGE_PAGES", "-u", "GLIBC_TUNABLES"}, "out.sid.h5");
  ASSERT_EQ(r.status, 0) << r.log;
  if (!transparent_huge_pages()) {
    EXPECT_NE(r.log.find("memory: 2 MiB heap pages off"), std::string::npos) << r.log;
    return;
  }
  EXPECT_NE(r.log.find(" as 2 MiB pages, the last "), std::string::npos) << r.log;
  EXPECT_NE(r.log.find(" as 4 KiB pages"), std::string::npos) << r.log;
}

// The probe's rule on the timings met on real machines. Source of each: the twenty-second
// session of tools/bench/reduce/RESULTS.md (an AMD EPYC Firecracker VM that reports free pages
// to its host) and the sixteenth (a paravirtualised VM whose 4 KiB faults took ~10 us).
namespace {
int walk(const std::vector<double>& pages, double small_2mib, int* walked) {
  std::vector<double> t;
  int verdict = FFR_PROBE_MORE;
  for (double seconds : pages) {
    t.push_back(seconds);
    verdict = ffr_huge_page_verdict(t.data(), static_cast<int>(t.size()), small_2mib);
    if (verdict != FFR_PROBE_MORE) break;
  }
  *walked = static_cast<int>(t.size());
  return verdict;
}
}  // namespace

TEST(HugePageVerdict, StopsWhenTheBackedPoolRunsOut) {
  // Firecracker VM: 8 MiB of 4 KiB pages in 4.4 ms (1.1 ms per 2 MiB); huge pages at 0.2 ms
  // from the blocks still backed (16 MiB here), then 4.5 ms (0.45 GB/s) each.
  std::vector<double> pages(8, 0.2e-3);
  pages.resize(FFR_PROBE_MAX_PAGES, 4.5e-3);
  int walked = 0;
  EXPECT_EQ(walk(pages, 1.1e-3, &walked), FFR_PROBE_OFF);
  EXPECT_EQ(walked, 8 + FFR_PROBE_SLOW_RUN);
}

TEST(HugePageVerdict, WalksTheWholeSampleWhenEveryPageIsFast) {
  std::vector<double> pages(FFR_PROBE_MAX_PAGES, 0.2e-3);
  pages[3] = pages[20] = pages[21] = 3e-3;  // isolated slow pages do not stop the walk
  int walked = 0;
  EXPECT_EQ(walk(pages, 1.1e-3, &walked), FFR_PROBE_ON);
  EXPECT_EQ(walked, FFR_PROBE_MAX_PAGES);
}

TEST(HugePageVerdict, PagesThatFellBackToSmallOnesDoNotPay) {
  // A 2 MiB page the kernel could not give is 512 faults of 4 KiB: as slow as the sample.
  std::vector<double> pages(FFR_PROBE_MAX_PAGES, 1.1e-3);
  int walked = 0;
  EXPECT_EQ(walk(pages, 1.1e-3, &walked), FFR_PROBE_OFF);
  EXPECT_EQ(walked, FFR_PROBE_SLOW_RUN);
}

TEST(HugePageVerdict, WhereFreePagesAreReportedOnlySlowSmallFaultsChooseHugePages) {
  // Firecracker VM, a fast walk of 64 MiB but 4 KiB pages at 1.1 ms per 2 MiB: the run was
  // slower with huge pages (3.63-4.11 s against 3.32-3.61 s).
  EXPECT_FALSE(ffr_huge_pages_pay(FFR_PROBE_ON, 1.1e-3, 1));
  // The paravirtualised VM: 8 MiB of 4 KiB pages in 21 ms (5.2 ms per 2 MiB), huge pages 9.1 -> 6.3 s.
  EXPECT_TRUE(ffr_huge_pages_pay(FFR_PROBE_ON, 5.2e-3, 1));
  // Without reporting the walk decides.
  EXPECT_TRUE(ffr_huge_pages_pay(FFR_PROBE_ON, 1.1e-3, 0));
  EXPECT_FALSE(ffr_huge_pages_pay(FFR_PROBE_OFF, 5.2e-3, 0));
  EXPECT_FALSE(ffr_huge_pages_pay(FFR_PROBE_OFF, 5.2e-3, 1));
}

TEST(Launcher, GlibcTunablesOfTheUserStand) {
  test::TempDir dir("tunables");
  write_bar(dir);
  const Launched r = launch(dir, {"FFR_HUGE_PAGES=on", "GLIBC_TUNABLES=glibc.malloc.hugetlb=0"}, "out.sid.h5");
  ASSERT_EQ(r.status, 0) << r.log;
  EXPECT_EQ(r.log.find("heap pages"), std::string::npos) << "the launcher chose over the user's tunable:\n" << r.log;
}

TEST(Launcher, MissingReductionProgramIsNamed) {
  test::TempDir dir("broken");
  std::filesystem::create_directories(dir / "bin");
  std::filesystem::copy_file(test::bin("ffr-reduce"), dir / "bin/ffr-reduce");
  const auto r = test::run((dir / "bin/ffr-reduce").string() + " --version");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("cannot start the reduction program"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("libexec/ffr/ffr-reduce-main"), std::string::npos) << r.output;
}

TEST(Launcher, GmshModuleIsLoadedOnlyForPartsThatNeedIt) {
  test::TempDir dir("no-gmsh");
  std::filesystem::create_directories(dir / "bin");
  std::filesystem::create_directories(dir / "libexec/ffr");
  std::filesystem::copy_file(test::bin("ffr-reduce"), dir / "bin/ffr-reduce");
  const std::filesystem::path build(FFR_BINARY_DIR);
  std::filesystem::copy_file(build / "libexec/ffr/ffr-reduce-main", dir / "libexec/ffr/ffr-reduce-main");
  const std::string reduce = (dir / "bin/ffr-reduce").string();
  EXPECT_EQ(test::run(reduce + " --version").status, 0);

  write_bar(dir);
  // Meshed by gmsh's command line into an MSH 4.1 file, which the program reads itself.
  test::gmsh_mesh(dir / "bar.geo", dir / "bar.msh", 0.012, 2);
  std::string part = formats::read_text_file(dir / "part.json");
  test::write_text(dir / "msh.json", part.replace(part.find("\"bar.geo\""), 9, "\"bar.msh\""));
  const auto from_msh = test::run(reduce + " " + (dir / "msh.json").string() + " -o " + (dir / "msh.sid.h5").string());
  EXPECT_EQ(from_msh.status, 0) << from_msh.output;

  const std::string geo = reduce + " " + (dir / "part.json").string() + " -o " + (dir / "geo.sid.h5").string();
  const auto missing = test::run(geo);
  EXPECT_EQ(missing.status, 1) << missing.output;
  EXPECT_NE(missing.output.find("libffr-gmsh.so was not found"), std::string::npos) << missing.output;
  EXPECT_NE(missing.output.find("FFR_GMSH_MODULE"), std::string::npos) << missing.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "geo.sid.h5"));

  const auto pointed = test::run("FFR_GMSH_MODULE=" + (build / "libexec/ffr/libffr-gmsh.so").string() + " " + geo);
  EXPECT_EQ(pointed.status, 0) << pointed.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "geo.sid.h5"));
}

TEST(Launcher, UnknownPageSettingIsBadInput) {
  const auto r = test::run("FFR_HUGE_PAGES=yes " + test::bin("ffr-reduce").string() + " --version");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("FFR_HUGE_PAGES"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("'yes'"), std::string::npos) << r.output;
}
