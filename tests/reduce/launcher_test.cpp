// bin/ffr-reduce is a launcher (preproc/launcher): it chooses the page size of the reduction's
// heap and starts libexec/ffr/ffr-reduce-main. The choice must change the page faults, never
// the result; the user's setting and glibc tunables stand; a broken installation is an error
// that names the missing program. gmsh's module (preproc/src/mesh/gmsh_module.hpp) is loaded
// only for a part that needs gmsh: without it the program starts and reads an MSH 4.1 file,
// and a geometry to mesh is refused naming the module, unless FFR_GMSH_MODULE points at it.
#include "ffr/formats/text_file.hpp"
#include "support.hpp"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <fstream>
#include <sstream>

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
  EXPECT_NE(r.log.find("8 MiB faulted in "), std::string::npos) << r.log;
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
