// The executables as a user's script drives them: --help/--version, exit codes 0/1/2,
// messages naming the file and dataset, the exact Campbell JSON of the contract, no partial
// output on failure.
#include "ffr/formats/campbell.hpp"
#include "ffr/formats/diff.hpp"
#include "ffr/formats/results_io.hpp"
#include "ffr/formats/sid_io.hpp"
#include "ffr/formats/synthetic.hpp"
#include "ffr/version.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <hdf5.h>
#include <sys/wait.h>

#include <algorithm>

#include <filesystem>
#include <fstream>
#include <sstream>

using namespace ffr::formats;
namespace fs = std::filesystem;

namespace {

fs::path dir() {
  static const fs::path d = fs::temp_directory_path() / ("ffr_cli_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}
struct RemoveTempDir : ::testing::Environment {
  void TearDown() override { fs::remove_all(dir()); }
};
const auto* const kCleanup = ::testing::AddGlobalTestEnvironment(new RemoveTempDir);

struct Outcome {
  int rc;
  std::string out, err;
};

std::string slurp(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

Outcome run(const std::string& tool, const std::string& args) {
  const fs::path out = dir() / "stdout.txt", err = dir() / "stderr.txt";
  // Under coreutils' timeout: a tool that hangs fails its test (status 124) instead of the suite.
  const std::string cmd = "timeout 120 " + std::string(FFR_BINARY_DIR) + "/bin/" + tool + " " + args + " >" + out.string() + " 2>" + err.string();
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

fs::path chain_file(const std::string& name, bool clamped = true) {
  synthetic::ChainParams p;
  p.clamped = clamped;
  p.EIy = p.EIz = 2.0;  // repeated pairs
  p.modes = 4;
  p.stiffening = true;
  const fs::path f = dir() / name;
  write_sid(synthetic::spring_chain(p).sid, f);
  return f;
}

}  // namespace

TEST(Cli, HelpAndVersion) {
  for (const std::string tool : {"ffr-info", "ffr-diff", "ffr-synth"}) {
    const Outcome h = run(tool, "--help");
    EXPECT_EQ(h.rc, 0) << tool;
    EXPECT_NE(h.out.find("usage: " + tool), std::string::npos) << h.out;
    const Outcome v = run(tool, "--version");
    EXPECT_EQ(v.rc, 0) << tool;
    EXPECT_NE(v.out.find(ffr::kVersion), std::string::npos) << v.out;
  }
}

TEST(Cli, InfoSummarisesASid) {
  const auto f = chain_file("info.sid.h5", false);
  const Outcome t = run("ffr-info", f.string());
  EXPECT_EQ(t.rc, 0) << t.err;
  EXPECT_NE(t.out.find("validation        OK"), std::string::npos) << t.out;
  const Outcome j = run("ffr-info", f.string() + " --json");
  ASSERT_EQ(j.rc, 0) << j.err;
  const auto js = nlohmann::json::parse(j.out);
  const Sid s = read_sid(f);
  EXPECT_EQ(js["kind"], "sid");
  EXPECT_DOUBLE_EQ(js["mass"].get<double>(), s.refmod.mass);
  EXPECT_EQ(js["nq"], 4);
  EXPECT_DOUBLE_EQ(js["modes"][2]["frequency_hz"].get<double>(), s.refmod.frequency_hz[2]);
  EXPECT_DOUBLE_EQ(js["center_of_mass"][0].get<double>(), 0.5);  // uniform chain on [0, 1]
  EXPECT_NEAR(js["inertia_about_com"][1][1].get<double>(), s.J.M0(1, 1) - 0.25, 1e-15);
  EXPECT_TRUE(js["validation"]["ok"].get<bool>());
  EXPECT_EQ(js["nodes"][1]["name"], "B");
}

TEST(Cli, InfoSummarisesAResultsFile) {
  Results r;
  r.time = Eigen::VectorXd::LinSpaced(11, 0.0, 1.0);
  r.outputs.push_back({"tip", "node_deformation", Eigen::MatrixXd::Random(11, 3)});
  r.outputs.push_back({"energy", "energy", Eigen::MatrixXd::Ones(11, 3)});
  r.steps = 10;
  r.newton_iterations = 23;
  r.integration_seconds = 0.5;
  const auto f = dir() / "run.h5";
  write_results(r, f);
  const Outcome j = run("ffr-info", f.string() + " --json");
  ASSERT_EQ(j.rc, 0) << j.err;
  const auto js = nlohmann::json::parse(j.out);
  EXPECT_EQ(js["kind"], "results");
  EXPECT_EQ(js["steps"], 10);
  EXPECT_EQ(js["newton_iterations"], 23);
  EXPECT_DOUBLE_EQ(js["time"]["end"].get<double>(), 1.0);
  EXPECT_EQ(js["outputs"][1]["name"], "tip");  // sorted by name
  EXPECT_DOUBLE_EQ(js["outputs"][1]["final"][2].get<double>(), r.outputs[0].values(10, 2));
  EXPECT_EQ(run("ffr-info", f.string()).rc, 0);
  // Ranges per component.
  EXPECT_DOUBLE_EQ(js["outputs"][1]["min"][0].get<double>(), r.outputs[0].values.col(0).minCoeff());
  EXPECT_DOUBLE_EQ(js["outputs"][1]["max"][1].get<double>(), r.outputs[0].values.col(1).maxCoeff());
  EXPECT_EQ(js["complete"], true);
  EXPECT_FALSE(js.contains("stopped_at"));
  // The samples of a run that stopped with a solver error (ffr-sim --keep-partial).
  r.stopped_at = 1.05;
  r.stop_reason = "Newton did not converge at t = 1.05 s";
  write_results(r, f);
  const Outcome s = run("ffr-info", f.string() + " --json");
  ASSERT_EQ(s.rc, 0) << s.err;
  const auto stopped = nlohmann::json::parse(s.out);
  EXPECT_EQ(stopped["complete"], false);
  EXPECT_DOUBLE_EQ(stopped["stopped_at"].get<double>(), 1.05);
  EXPECT_EQ(stopped["stop_reason"], r.stop_reason);
  const Outcome text = run("ffr-info", f.string());
  EXPECT_NE(text.out.find("stopped           at t = 1.05 s, before its end: Newton did not converge at t = 1.05 s"),
            std::string::npos) << text.out;
  const Outcome plot = run("ffr-info", f.string() + " --plot tip --png " + (dir() / "stopped.png").string());
  ASSERT_EQ(plot.rc, 0) << plot.err;
  EXPECT_NE(plot.out.find("holds a run that stopped at t = 1.05 s, before its end"), std::string::npos) << plot.out;
}

TEST(Cli, InfoPlotsTimeHistoriesAndRefusesUnknownChannels) {
  Results r;
  r.time = Eigen::VectorXd::LinSpaced(21, 0.0, 2.0);
  r.outputs.push_back({"tip", "node_deformation", Eigen::MatrixXd::Random(21, 3)});
  r.outputs.push_back({"angle", "joint_coordinate", Eigen::MatrixXd::Constant(21, 1, 0.5)});  // flat: no range
  const auto f = dir() / "plot_run.h5";
  write_results(r, f);
  const auto png = dir() / "histories.png";
  const Outcome ok = run("ffr-info", f.string() + " --plot tip,angle,tip[2] --png " + png.string());
  ASSERT_EQ(ok.rc, 0) << ok.err;
  const std::string bytes = slurp(png);
  ASSERT_GT(bytes.size(), 33u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  const auto u32 = [&](int at) {
    unsigned v = 0;
    for (int i = 0; i < 4; ++i) v = v * 256 + static_cast<unsigned char>(bytes[at + i]);
    return v;
  };
  EXPECT_EQ(u32(16), 900u);      // width
  EXPECT_EQ(u32(20), 3 * 360u);  // one 360-pixel panel per channel
  const auto bad = dir() / "bad.png";
  const Outcome unknown = run("ffr-info", f.string() + " --plot tip,speed --png " + bad.string());
  EXPECT_EQ(unknown.rc, 2);
  EXPECT_NE(unknown.err.find(f.string() + ": no output channel 'speed'"), std::string::npos) << unknown.err;
  EXPECT_EQ(run("ffr-info", f.string() + " --plot tip[3] --png " + bad.string()).rc, 2);
  EXPECT_EQ(run("ffr-info", f.string() + " --plot tip[x] --png " + bad.string()).rc, 2);
  EXPECT_EQ(run("ffr-info", f.string() + " --plot tip").rc, 2);  // no --png
  EXPECT_FALSE(fs::exists(bad));
  // --png naming the results file replaced them by the picture (exit 0).
  const Outcome over = run("ffr-info", f.string() + " --plot tip --png " + (dir() / "." / "plot_run.h5").string());
  EXPECT_EQ(over.rc, 2);
  EXPECT_NE(over.err.find("would overwrite the results file " + f.string()), std::string::npos) << over.err;
  EXPECT_EQ(run("ffr-info", f.string() + " --json").rc, 0);  // still the results file
}

// A model file may name an output "x[mm]" or "a,b": --plot takes a channel's whole name before
// reading a trailing [i] as a component ("x[mm][1]"), and the longest comma-separated run of
// pieces that names a channel.
TEST(Cli, InfoPlotsChannelsWhoseNamesHoldBracketsOrCommas) {
  Results r;
  r.time = Eigen::VectorXd::LinSpaced(11, 0.0, 1.0);
  r.outputs.push_back({"x[mm]", "", Eigen::MatrixXd::Random(11, 2)});
  r.outputs.push_back({"a,b", "", Eigen::MatrixXd::Random(11, 1)});
  r.outputs.push_back({"a", "", Eigen::MatrixXd::Random(11, 1)});
  const auto f = dir() / "bracket_run.h5";
  write_results(r, f);
  const auto png = dir() / "bracket.png";
  const Outcome whole = run("ffr-info", f.string() + " --plot 'x[mm]' --png " + png.string());
  EXPECT_EQ(whole.rc, 0) << whole.err;
  EXPECT_TRUE(fs::exists(png));
  const Outcome component = run("ffr-info", f.string() + " --plot 'x[mm][1]' --png " + png.string());
  EXPECT_EQ(component.rc, 0) << component.err;
  const Outcome commas = run("ffr-info", f.string() + " --plot 'a,b,a,x[mm][0],a,b[0]' --png " + png.string());
  ASSERT_EQ(commas.rc, 0) << commas.err;
  std::ifstream in(png, std::ios::binary);
  unsigned char header[24] = {};
  in.read(reinterpret_cast<char*>(header), sizeof header);
  EXPECT_EQ((header[20] << 24) | (header[21] << 16) | (header[22] << 8) | header[23], 4 * 360);  // four panels
  const Outcome other = run("ffr-info", f.string() + " --plot 'x[cm]' --png " + png.string());
  EXPECT_EQ(other.rc, 2);
  EXPECT_NE(other.err.find("'x[cm]' is neither NAME nor NAME[i]"), std::string::npos) << other.err;
}

// A channel flat to its last bits far from zero (a coordinate held by a joint, rounding noise
// of 1 ulp at 1.0): the axis's tick step is below the values' spacing, so adding it to a tick
// value changes nothing. The plot must still end, with ticks that are distinct numbers.
TEST(Cli, InfoPlotsAChannelFlatToRoundingFarFromZero) {
  Results r;
  r.time.setConstant(5, 1e9);  // and times spanning one ulp of 1e9
  r.time[4] = std::nextafter(1e9, 2e9);
  Eigen::MatrixXd z(5, 1);
  z << 1.0, std::nextafter(1.0, 2.0), 1.0, std::nextafter(1.0, 2.0), 1.0;
  r.outputs.push_back({"z", "node_position", z});
  const auto f = dir() / "flat_run.h5";
  write_results(r, f);
  const auto png = dir() / "flat.png";
  const Outcome ok = run("ffr-info", f.string() + " --plot z --png " + png.string());
  ASSERT_EQ(ok.rc, 0) << ok.err;
  EXPECT_EQ(slurp(png).substr(1, 3), "PNG");
  // Values whose span overflows a double: refused naming the file and channel, no picture.
  r.outputs.push_back({"wide", "node_position", Eigen::MatrixXd::Constant(5, 1, 1e308)});
  r.outputs.back().values(2, 0) = -1e308;
  write_results(r, f);
  const auto none = dir() / "none.png";
  const Outcome wide = run("ffr-info", f.string() + " --plot z,wide --png " + none.string());
  EXPECT_EQ(wide.rc, 2);
  EXPECT_NE(wide.err.find(f.string() + ": output channel 'wide': a plot's range is not a finite number"), std::string::npos) << wide.err;
  EXPECT_FALSE(fs::exists(none));
}

TEST(Cli, InfoRefusesBadInputWithExitCode2) {
  const Outcome missing = run("ffr-info", (dir() / "nowhere.h5").string());
  EXPECT_EQ(missing.rc, 2);
  EXPECT_NE(missing.err.find("nowhere.h5"), std::string::npos) << missing.err;
  const auto f = dir() / "text.h5";
  std::ofstream(f) << "not hdf5";
  EXPECT_EQ(run("ffr-info", f.string()).rc, 2);
  EXPECT_EQ(run("ffr-info", "").rc, 2);
  EXPECT_EQ(run("ffr-info", "a.h5 --bogus").rc, 2);
  // A SID with a dataset removed: the message names file and dataset.
  const auto g = chain_file("damaged.sid.h5");
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t h = H5Fopen(g.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(h, 0);
  H5Ldelete(h, "/sid/Oe/M1", H5P_DEFAULT);
  H5Fclose(h);
  const Outcome damaged = run("ffr-info", g.string() + " --json");
  EXPECT_EQ(damaged.rc, 2);
  EXPECT_NE(damaged.err.find(g.string() + ": /sid/Oe/M1: missing dataset"), std::string::npos) << damaged.err;
  EXPECT_TRUE(damaged.out.empty()) << "no partial output: " << damaged.out;
  EXPECT_EQ(std::count(damaged.err.begin(), damaged.err.end(), '\n'), 1) << "one line: " << damaged.err;
}

TEST(Cli, CampbellJsonIsExactlyTheContract) {
  const auto f = chain_file("campbell.sid.h5");
  const Outcome j = run("ffr-info", f.string() + " --campbell z --speeds 0,50,100 --json");
  ASSERT_EQ(j.rc, 0) << j.err;
  const auto js = nlohmann::ordered_json::parse(j.out);
  ASSERT_EQ(js.size(), 2u);
  EXPECT_EQ(js.begin().key(), "speeds_rad_s");
  EXPECT_EQ(std::next(js.begin()).key(), "frequency_hz");
  EXPECT_EQ(js["speeds_rad_s"], nlohmann::json({0.0, 50.0, 100.0}));
  const auto ref = campbell(read_sid(f), 2, {0.0, 50.0, 100.0});
  ASSERT_EQ(js["frequency_hz"].size(), 3u);
  for (int s = 0; s < 3; ++s) {
    ASSERT_EQ(js["frequency_hz"][s].size(), 4u);
    for (int k = 0; k < 4; ++k) EXPECT_DOUBLE_EQ(js["frequency_hz"][s][k].get<double>(), ref.frequency_hz[s][k]);
    for (int k = 1; k < 4; ++k) EXPECT_LE(js["frequency_hz"][s][k - 1].get<double>(), js["frequency_hz"][s][k].get<double>());
  }
  const Outcome t = run("ffr-info", f.string() + " --campbell x --speeds 0,10");
  EXPECT_EQ(t.rc, 0);
  EXPECT_NE(t.out.find("speed [rad/s]"), std::string::npos);
}

TEST(Cli, CampbellPngAndBadArguments) {
  const auto f = chain_file("png.sid.h5");
  const auto png = dir() / "campbell.png";
  ASSERT_EQ(run("ffr-info", f.string() + " --campbell y --speeds 0,20,40 --png " + png.string()).rc, 0);
  const std::string bytes = slurp(png);
  ASSERT_GT(bytes.size(), 33u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  EXPECT_EQ(bytes.substr(12, 4), "IHDR");
  EXPECT_EQ(static_cast<unsigned char>(bytes[18]) * 256 + static_cast<unsigned char>(bytes[19]), 900);  // width
  const Outcome axis = run("ffr-info", f.string() + " --campbell w --speeds 0");
  EXPECT_EQ(axis.rc, 2);
  EXPECT_NE(axis.err.find("--campbell"), std::string::npos);
  EXPECT_EQ(run("ffr-info", f.string() + " --speeds 0,1").rc, 2);
  EXPECT_EQ(run("ffr-info", f.string() + " --campbell x --speeds 0,abc").rc, 2);
  // No partial output when the PNG cannot be written.
  const auto nowhere = dir() / "no_such_dir" / "c.png";
  EXPECT_NE(run("ffr-info", f.string() + " --campbell y --speeds 0 --png " + nowhere.string()).rc, 0);
  EXPECT_FALSE(fs::exists(nowhere));
}

TEST(Cli, DiffExitCodes) {
  const auto a = chain_file("a.sid.h5");
  const Sid sa = read_sid(a);
  // B: the same body with flipped signs and a rotation inside the first repeated pair.
  Eigen::MatrixXd T = Eigen::MatrixXd::Identity(4, 4);
  const double c = std::cos(0.7), s = std::sin(0.7);
  T.topLeftCorner(2, 2) << c, -s, s, c;
  T(3, 3) = -1;
  const auto b = dir() / "b.sid.h5";
  write_sid(transform_modes(sa, T), b);
  const Outcome same = run("ffr-diff", a.string() + " " + b.string());
  EXPECT_EQ(same.rc, 0) << same.out << same.err;
  EXPECT_NE(same.out.find("EQUIVALENT"), std::string::npos);

  Sid sc = sa;
  sc.Gr[2](1, 2) += 1e-3;
  const auto cfile = dir() / "c.sid.h5";
  write_sid(sc, cfile);
  const Outcome diff = run("ffr-diff", a.string() + " " + cfile.string());
  EXPECT_EQ(diff.rc, 1);
  EXPECT_NE(diff.out.find("/sid/Gr/M0[2,1,2]"), std::string::npos) << diff.out;
  EXPECT_EQ(run("ffr-diff", a.string() + " " + cfile.string() + " --rtol 1e-2").rc, 0);
  EXPECT_EQ(run("ffr-diff", a.string() + " " + cfile.string() + " --atol 1e-2").rc, 0);

  const Outcome bad = run("ffr-diff", a.string() + " " + (dir() / "missing.sid.h5").string());
  EXPECT_EQ(bad.rc, 2);
  EXPECT_NE(bad.err.find("missing.sid.h5"), std::string::npos);
  EXPECT_EQ(run("ffr-diff", a.string()).rc, 2);
  EXPECT_EQ(run("ffr-diff", a.string() + " " + b.string() + " --rtol -1").rc, 2);
}

TEST(Cli, SynthWritesAValidChainAndLeavesNothingOnError) {
  const auto f = dir() / "synth.sid.h5";
  const Outcome ok = run("ffr-synth", "--chain --points 7 --modes 3 --clamped --stiffening -o " + f.string());
  ASSERT_EQ(ok.rc, 0) << ok.err;
  EXPECT_EQ(read_sid(f).nq(), 3);
  EXPECT_EQ(read_sid(f).refmod.reference, "clamped:A");
  const auto g = dir() / "bad_synth.sid.h5";
  EXPECT_EQ(run("ffr-synth", "--chain --points 1 -o " + g.string()).rc, 2);
  EXPECT_EQ(run("ffr-synth", "--chain --modes 99 -o " + g.string()).rc, 2);
  EXPECT_FALSE(fs::exists(g));
  for (const auto& e : fs::directory_iterator(dir()))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << "left behind: " << e.path();
}

TEST(Cli, InfoExitsTwoForASidFailingValidationAfterItsSummary) {
  synthetic::ChainParams p;
  p.modes = 4;
  Sid s = synthetic::spring_chain(p).sid;
  s.Gr[1](0, 1) += 0.5;  // breaks Gr against the integrals (identities: ffr-sim would only note them)
  const fs::path f = dir() / "invalid.sid.h5";
  write_sid(s, f);
  const Outcome t = run("ffr-info", f.string());
  EXPECT_EQ(t.rc, 2) << t.err;
  EXPECT_NE(t.out.find("validation        FAILED"), std::string::npos) << t.out;
  EXPECT_NE(t.err.find(f.string() + ": fails "), std::string::npos) << t.err;
  EXPECT_NE(t.err.find("first Gr = 2 tr(R_k) I - 2 R_k^T (/sid/Gr/M0 /integrals/rPdm)"), std::string::npos) << t.err;
  EXPECT_EQ(std::count(t.err.begin(), t.err.end(), '\n'), 1) << t.err;
  const Outcome j = run("ffr-info", f.string() + " --json");
  EXPECT_EQ(j.rc, 2);
  EXPECT_FALSE(nlohmann::json::parse(j.out)["validation"]["ok"].get<bool>());
}

TEST(Cli, InfoJsonNeverFailsOnStringsThatAreNotUtf8) {
  // A node name with bytes that are not UTF-8 made --json exit 1 with type_error.316.
  synthetic::ChainParams p;
  Sid s = synthetic::spring_chain(p).sid;
  s.nodes[1].name = "B\xff\xfe";
  s.provenance.extra["note"] = "\xc3\x28";
  const fs::path f = dir() / "latin.sid.h5";
  write_sid(s, f);
  const Outcome j = run("ffr-info", f.string() + " --json");
  ASSERT_EQ(j.rc, 0) << j.err;
  const auto js = nlohmann::json::parse(j.out);  // valid JSON: the bad bytes are U+FFFD
  EXPECT_EQ(js["nodes"][1]["name"].get<std::string>(), "B\xEF\xBF\xBD\xEF\xBF\xBD");
  EXPECT_EQ(run("ffr-info", f.string()).rc, 0);
}

TEST(Cli, DamagedFilesAreRefusedByInfoAndDiffNamingFileAndDataset) {
  const auto a = chain_file("sealed_a.sid.h5");
  const auto b = chain_file("sealed_b.sid.h5");
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t h = H5Fopen(b.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(h, 0);
  const hid_t ds = H5Dopen2(h, "/sid/Oe/M0", H5P_DEFAULT);
  std::vector<double> v(24);
  H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  v[3] *= 1.5;
  H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Dclose(ds);
  H5Fclose(h);
  for (const auto& [tool, args] : {std::pair<std::string, std::string>{"ffr-info", b.string()},
                                   std::pair<std::string, std::string>{"ffr-diff", a.string() + " " + b.string()}}) {
    const Outcome o = run(tool, args);
    EXPECT_EQ(o.rc, 2) << tool;
    EXPECT_NE(o.err.find(b.string() + ": /sid/Oe/M0: content checksum mismatch"), std::string::npos) << tool << ": " << o.err;
    EXPECT_TRUE(o.out.empty()) << o.out;
  }
}
