// ffr-sim as a user runs it: exit status 0 / 2 (bad input) / 1 (other failure), one-line
// messages naming the file and field, the results file with the contract's datasets and
// attributes, the CSV header, and no output file left behind on failure.
#include "ffr/formats/h5.hpp"
#include "ffr/formats/results_io.hpp"
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <thread>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>
#include <sys/wait.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <unistd.h>

namespace {

const std::string kSim = std::string(FFR_BINARY_DIR) + "/bin/ffr-sim";

using Result = ffr::runtime::test::SimRun;
Result run(const std::string& args) { return ffr::runtime::test::run_ffr_sim(args); }

const char* kPendulum = R"({
  "gravity": [0, 0, -9.81],
  "bodies": [{"name": "bar", "type": "rigid", "mass": 1.0, "com": [0.5, 0, 0],
              "inertia": [[1e-4, 0, 0], [0, 0.0834, 0], [0, 0, 0.0834]]}],
  "joints": [{"name": "hinge", "type": "revolute", "body1": "ground", "body2": "bar", "at": [0, 0, 0], "axis": [0, 1, 0]}],
  "solver": {"end": 0.1, "step": 0.001%s},
  "outputs": [{"name": "angle", "type": "joint_coordinate", "joint": "hinge"}, {"name": "energy", "type": "energy"}]
})";

std::string pendulum(const std::string& extra = "") {
  char buf[2048];
  std::snprintf(buf, sizeof buf, kPendulum, extra.c_str());
  return buf;
}

}  // namespace

TEST(Cli, HelpAndVersion) {
  const Result h = run("--help");
  EXPECT_EQ(h.status, 0);
  EXPECT_NE(h.output.find("usage: ffr-sim MODEL.json -o OUT.h5"), std::string::npos) << h.output;
  const Result v = run("--version");
  EXPECT_EQ(v.status, 0);
  EXPECT_NE(v.output.find("ffr-sim"), std::string::npos) << v.output;
}

TEST(Cli, RunWritesResultsAndCsv) {
  ffr::runtime::test::TempDir dir("cli");
  ffr::runtime::test::write_text(dir / "m.json", pendulum());
  const Result r = run((dir / "m.json").string() + " -o " + (dir / "out.h5").string() + " --csv " + (dir / "out.csv").string());
  ASSERT_EQ(r.status, 0) << r.output;
  ffr::formats::h5::Reader h5(dir / "out.h5");
  EXPECT_EQ(h5.shape("/time"), (ffr::formats::h5::Shape{101}));
  EXPECT_EQ(h5.shape("/outputs/angle"), (ffr::formats::h5::Shape{101, 1}));
  EXPECT_EQ(h5.shape("/outputs/energy"), (ffr::formats::h5::Shape{101, 3}));
  EXPECT_EQ(h5.attr_int("/", "steps"), 100);
  EXPECT_GE(h5.attr_int("/", "newton_iterations"), 100);
  // Every step builds at least one tangent and solves with it at least once an iteration.
  EXPECT_GE(h5.attr_int("/", "factorizations"), 100);
  EXPECT_LE(h5.attr_int("/", "factorizations"), h5.attr_int("/", "newton_iterations") + 1);
  EXPECT_GE(h5.attr_int("/", "solves"), h5.attr_int("/", "newton_iterations"));
  EXPECT_GT(h5.attr_double("/", "integration_seconds"), 0.0);
  std::ifstream csv(dir / "out.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header, "time,angle[0],energy[0],energy[1],energy[2]");
}

// Output names may hold a comma or a quote (JSON strings); the CSV header quotes such a field
// (RFC 4180), so that a CSV reader finds one heading per column.
TEST(Cli, CsvHeaderQuotesNamesWithCommasAndQuotes) {
  ffr::runtime::test::TempDir dir("cli");
  std::string model = pendulum();
  const std::string plain = R"("name": "angle")", odd = R"("name": "hinge, \"deg\"")";
  model.replace(model.find(plain), plain.size(), odd);
  ffr::runtime::test::write_text(dir / "m.json", model);
  const Result r = run((dir / "m.json").string() + " -o " + (dir / "out.h5").string() + " --csv " + (dir / "out.csv").string());
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream csv(dir / "out.csv");
  std::string header, row;
  std::getline(csv, header);
  std::getline(csv, row);
  EXPECT_EQ(header, R"(time,"hinge, ""deg""[0]",energy[0],energy[1],energy[2])");
  EXPECT_EQ(std::count(row.begin(), row.end(), ','), 4) << row;  // five values under five headings
}

TEST(Cli, BadInputIsExitTwoWithFileAndField) {
  ffr::runtime::test::TempDir dir("cli");
  ffr::runtime::test::write_text(dir / "m.json", pendulum(R"(, "tolerance": -1)"));
  const Result r = run((dir / "m.json").string() + " -o " + (dir / "out.h5").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("m.json: solver.tolerance: expected a positive number"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
  ffr::runtime::test::write_text(dir / "m.json", pendulum(R"(, "newton_tolerance": 0)"));
  const Result r2 = run((dir / "m.json").string() + " -o " + (dir / "out.h5").string());
  EXPECT_EQ(r2.status, 2) << r2.output;
  EXPECT_NE(r2.output.find("m.json: solver.newton_tolerance: expected a positive number"), std::string::npos) << r2.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));

  ffr::runtime::test::write_text(dir / "broken.json", "{\"bodies\": [");
  EXPECT_EQ(run((dir / "broken.json").string() + " -o " + (dir / "out.h5").string()).status, 2);
  EXPECT_EQ(run((dir / "missing.json").string() + " -o " + (dir / "out.h5").string()).status, 2);
  EXPECT_EQ(run((dir / "m.json").string()).status, 2);  // no -o
  EXPECT_EQ(run("--bogus").status, 2);
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
}

TEST(Cli, NewtonFailureIsExitOneWithTimeAndResidual) {
  ffr::runtime::test::TempDir dir("cli");
  // One Newton iteration cannot reach the tolerance: the solver must give up cleanly.
  ffr::runtime::test::write_text(dir / "m.json", pendulum(R"(, "max_iterations": 1, "newton_tolerance": 1e-15)"));
  const Result r = run((dir / "m.json").string() + " -o " + (dir / "out.h5").string() + " --csv " + (dir / "out.csv").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("Newton did not converge at t = 0.001 s"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("scaled increment"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
  EXPECT_FALSE(std::filesystem::exists(dir / "out.csv"));
}

// A run that fails halfway: by default nothing is written (the note says how to keep it); with
// --keep-partial the samples before the failed step are written, marked as stopped, and they
// are the samples of the same run ended before the failure, bit for bit.
TEST(Cli, KeepPartialWritesTheSamplesBeforeAFailedStep) {
  ffr::runtime::test::TempDir dir("cli");
  // A vertical force rising from 0 at t = 0.0505 s to 1e29 N half a millisecond later: the step
  // that meets it cannot converge.
  const std::string force = R"("forces": [{"type": "point_force", "body": "bar", "at": [1, 0, 0],
      "table": {"t": [0, 0.0505, 0.051], "value": [[0, 0, 0], [0, 0, 0], [0, 0, 1e29]]}}],
  "solver":)";
  std::string failing = pendulum(), until = pendulum();
  failing.replace(failing.find("\"solver\":"), 9, force);
  until.replace(until.find("\"solver\":"), 9, force);
  until.replace(until.find("\"end\": 0.1"), 10, "\"end\": 0.05");
  ffr::runtime::test::write_text(dir / "m.json", failing);
  ffr::runtime::test::write_text(dir / "until.json", until);
  const std::string model = (dir / "m.json").string(), h5 = (dir / "out.h5").string(), csv = (dir / "out.csv").string();

  const Result plain = run(model + " -o " + h5 + " --csv " + csv);
  ASSERT_EQ(plain.status, 1) << plain.output;
  EXPECT_NE(plain.output.find("nothing written; run again with --keep-partial to keep the 51 samples recorded to t = 0.05 s"), std::string::npos) << plain.output;
  EXPECT_FALSE(std::filesystem::exists(h5));
  EXPECT_FALSE(std::filesystem::exists(csv));

  const std::string pvd = (dir / "run.pvd").string();
  const Result kept = run(model + " -o " + h5 + " --csv " + csv + " --vtk " + pvd + " --keep-partial");
  ASSERT_EQ(kept.status, 1) << kept.output;
  const auto partial = ffr::formats::read_results(h5);
  ASSERT_TRUE(partial.stopped_at.has_value());
  EXPECT_GT(*partial.stopped_at, 0.05);
  EXPECT_LT(*partial.stopped_at, 0.1);
  EXPECT_NE(kept.output.find(partial.stop_reason), std::string::npos) << kept.output;  // the error printed
  EXPECT_NE(partial.stop_reason.find("t = "), std::string::npos) << partial.stop_reason;
  // Every sample before the failed step, one a step: the last one a step before it.
  const auto nt = partial.time.size();
  ASSERT_GE(nt, 51);
  EXPECT_NEAR(partial.time[nt - 1], *partial.stopped_at - 0.001, 1e-12);
  std::ifstream in(csv);
  const auto lines = std::count(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>(), '\n');
  EXPECT_EQ(lines, nt + 1);  // the header and one line a sample
  std::ifstream collection(pvd);
  const std::string frames((std::istreambuf_iterator<char>(collection)), std::istreambuf_iterator<char>());
  std::size_t datasets = 0;
  for (auto at = frames.find("<DataSet"); at != std::string::npos; at = frames.find("<DataSet", at + 1)) ++datasets;
  EXPECT_EQ(datasets, static_cast<std::size_t>(nt));  // a ParaView frame a sample

  // A run that failed has no state to go on from (it needs a change to the model), and the
  // frames before a stop are not in a results file: both refused before any work.
  const Result again = run(model + " -o " + (dir / "again.h5").string() + " --resume " + h5);
  EXPECT_EQ(again.status, 2) << again.output;
  EXPECT_NE(again.output.find("--resume " + h5 + ": /restart: no state to resume from"), std::string::npos) << again.output;
  const Result with_vtk = run(model + " -o " + (dir / "again.h5").string() + " --resume " + h5 + " --vtk " + (dir / "again.pvd").string());
  EXPECT_EQ(with_vtk.status, 2) << with_vtk.output;
  EXPECT_NE(with_vtk.output.find("--vtk with --resume"), std::string::npos) << with_vtk.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "again.h5"));

  const Result whole = run((dir / "until.json").string() + " -o " + (dir / "until.h5").string());
  ASSERT_EQ(whole.status, 0) << whole.output;
  const auto reference = ffr::formats::read_results(dir / "until.h5");
  EXPECT_FALSE(reference.stopped_at.has_value());
  ASSERT_EQ(reference.time.size(), 51);
  for (const char* name : {"angle", "energy"})
    EXPECT_EQ(partial.find(name)->values.topRows(51), reference.find(name)->values) << name;
}

// Ctrl-C on a long run with --keep-partial: the run stops after its current step, writes the
// samples it has with the state it reached, and the process then ends by the signal itself (the
// shell sees 128 + SIGINT). The process is started with SIGINT at its default action (a
// non-interactive shell's background job would ignore it, and ffr-sim leaves an ignored signal so).
TEST(Cli, KeepPartialWritesWhatARunHasWhenInterrupted) {
  ffr::runtime::test::TempDir dir("cli");
  // 1e7 steps (tens of seconds): still running when the signal comes; a sample every 1000 steps.
  std::string model = pendulum(R"(, "output_every": 1000)");
  model.replace(model.find("\"end\": 0.1"), 10, "\"end\": 1e4");
  ffr::runtime::test::write_text(dir / "m.json", model);
  const std::string m = (dir / "m.json").string(), h5 = (dir / "out.h5").string(), err = (dir / "err.txt").string();
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t defaults;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGINT);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGDEF);
  const char* argv[] = {kSim.c_str(), m.c_str(), "-o", h5.c_str(), "--keep-partial", nullptr};
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, kSim.c_str(), &files, &attr, const_cast<char* const*>(argv), environ), 0);
  posix_spawn_file_actions_destroy(&files);
  posix_spawnattr_destroy(&attr);
  // The first progress line (after 2 s of stepping) says the time loop is running.
  std::string text;
  for (int i = 0; i < 1200 && text.find("ffr-sim: t = ") == std::string::npos; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    std::ifstream in(err);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  ASSERT_NE(text.find("ffr-sim: t = "), std::string::npos) << text;
  // Twice within a moment, as `timeout` sends it (to the process, then to its group): one request.
  ASSERT_EQ(kill(pid, SIGINT), 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ASSERT_EQ(kill(pid, SIGINT), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  std::ifstream in(err);
  text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  ASSERT_TRUE(WIFSIGNALED(status)) << text;
  EXPECT_EQ(WTERMSIG(status), SIGINT);
  EXPECT_NE(text.find("interrupted by SIGINT at t = "), std::string::npos) << text;
  const auto r = ffr::formats::read_results(h5);
  ASSERT_TRUE(r.stopped_at.has_value());
  EXPECT_EQ(r.stop_reason, "interrupted by SIGINT");
  EXPECT_TRUE(ffr::formats::h5::Reader(h5).exists("/restart/state"));  // ffr-sim --resume goes on from it (resume_test.cpp)
  EXPECT_GT(*r.stopped_at, 1.0);
  EXPECT_LT(*r.stopped_at, 1e4);
  ASSERT_GE(r.time.size(), 2);
  EXPECT_EQ(r.time[r.time.size() - 1], *r.stopped_at);  // the state it reached is the last sample
  EXPECT_NEAR(r.time[r.time.size() - 2], std::ceil(*r.stopped_at - 1e-9) - 1, 1e-6);  // a sample every 1 s before it
}

TEST(Cli, OutputsThatCannotBeWrittenAreRefusedBeforeTheRun) {
  ffr::runtime::test::TempDir dir("cli");
  ffr::runtime::test::write_text(dir / "m.json", pendulum());
  const std::string model = (dir / "m.json").string(), h5 = (dir / "out.h5").string();
  // A CSV in a directory that does not exist: before, the results file was already in place
  // when the CSV failed (exit 1).
  Result r = run(model + " -o " + h5 + " --csv " + (dir / "nowhere" / "out.csv").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--csv"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("no directory"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
  // The CSV named like the results file replaced them (exit 0, an HDF5 file that was text).
  r = run(model + " -o " + h5 + " --csv " + (dir / "." / "out.h5").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--csv " + (dir / "." / "out.h5").string() + " names the same file as -o " + h5), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
  r = run(model + " -o " + (dir / "no" / "out.h5").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("-o"), std::string::npos) << r.output;
}

// An output naming an input, or the results and the ParaView collection naming one file: the
// model file was replaced by the results (exit 0), -o and --vtk under one name left the
// collection where the results should be. Refused before the run, the inputs untouched.
TEST(Cli, OutputsThatWouldOverwriteAnInputOrEachOtherAreRefused) {
  ffr::runtime::test::TempDir dir("cli");
  ffr::formats::synthetic::ChainParams p;
  p.clamped = true;
  ffr::runtime::test::write_sid_file(ffr::formats::synthetic::spring_chain(p).sid, dir / "chain.sid.h5");
  const std::string model_text = R"({"bodies": [{"name": "c", "type": "flexible", "sid": "chain.sid.h5"}],
    "joints": [{"name": "clamp", "type": "fixed", "body1": "ground", "body2": "c", "node2": "A"}],
    "solver": {"end": 0.01, "step": 0.001}})";
  ffr::runtime::test::write_text(dir / "m.json", model_text);
  const std::string model = (dir / "m.json").string(), sid = (dir / "chain.sid.h5").string();
  const std::string sid_before = [&] {
    std::ifstream in(sid, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }();
  struct Case { std::string args, expect; };
  const std::vector<Case> cases = {
      {"-o " + model, "-o " + model + " would overwrite the model file " + model},
      {"-o " + (dir / "out.h5").string() + " --csv " + (dir / "sub" / ".." / "m.json").string(), "would overwrite the model file"},
      {"-o " + (dir / "." / "chain.sid.h5").string(), "would overwrite the SID file " + sid},
      {"-o " + (dir / "run.pvd").string() + " --vtk " + (dir / "run.pvd").string(), "--vtk " + (dir / "run.pvd").string() + " names the same file as -o"},
      // A folder as the results file: the run took place, then the rename into place failed.
      {"-o " + (dir / "sub").string(), "-o " + (dir / "sub").string() + ": is a folder"},
  };
  std::filesystem::create_directory(dir / "sub");
  for (const auto& c : cases) {
    const Result r = run(model + " " + c.args);
    EXPECT_EQ(r.status, 2) << c.args << ": " << r.output;
    EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << ": " << r.output;
  }
  std::ifstream in(model);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), model_text);
  std::ifstream sin(sid, std::ios::binary);
  EXPECT_TRUE(std::string(std::istreambuf_iterator<char>(sin), {}) == sid_before);
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
  EXPECT_FALSE(std::filesystem::exists(dir / "run.pvd"));
  // The same model writes its results beside its inputs.
  const Result ok = run(model + " -o " + (dir / "out.h5").string() + " --quiet");
  EXPECT_EQ(ok.status, 0) << ok.output;
}

TEST(Cli, RecordingMoreThanMemoryHoldsIsRefusedNotAnAllocationFailure) {
  // 1e8 steps recorded from the start need more than the 2 GB of address space given here:
  // it was "std::bad_alloc", exit 1 (found by fuzzing).
#if defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer reserves terabytes of address space for its shadow memory at start-up,
  // so under `ulimit -v` the instrumented ffr-sim cannot start at all.
  GTEST_SKIP() << "ulimit -v and AddressSanitizer's shadow memory exclude each other";
#endif
  ffr::runtime::test::TempDir dir("cli");
  std::string m = pendulum();
  const std::string end = "\"end\": 0.1";
  m.replace(m.find(end), end.size(), "\"end\": 1e5");
  ffr::runtime::test::write_text(dir / "m.json", m);
  const std::string cmd = "ulimit -v 2000000; " + kSim + " " + (dir / "m.json").string() + " -o " + (dir / "out.h5").string() + " -q 2>&1";
  FILE* p = popen(("sh -c '" + cmd + "'").c_str(), "r");
  std::string out;
  std::array<char, 512> buf{};
  while (fgets(buf.data(), buf.size(), p)) out += buf.data();
  const int st = pclose(p);
  EXPECT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 2) << out;
  EXPECT_NE(out.find("m.json: solver.output_every: the outputs of 100000002 recorded steps do not fit in memory"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
}
