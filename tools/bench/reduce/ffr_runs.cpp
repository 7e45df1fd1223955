#include "ffr_runs.hpp"

#include "ffr/formats/h5.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace ffr::bench {
namespace fs = std::filesystem;
namespace {

void write_file(const fs::path& p, const std::string& text) {
  std::ofstream f(p);
  f << text;
  if (!f) throw std::runtime_error("cannot write " + p.string());
}

std::string material_fields(const IsoMaterial& m) {
  std::ostringstream o;
  o.precision(17);
  o << "\"E\": " << m.E << ", \"nu\": " << m.nu << ", \"rho\": " << m.rho;
  return o.str();
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(' ');
  const auto e = s.find_last_not_of(' ');
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

}  // namespace

void write_solid_part(const fs::path& json, const fs::path& msh, const IsoMaterial& mat, int modes) {
  write_file(json, "{\"comment\": \"reduce_bench: plate with holes, clamped at x = 0\",\n"
                   " \"geometry\": \"" + msh.filename().string() + "\",\n"
                   " \"materials\": [{\"group\": \"body\", " + material_fields(mat) + "}],\n"
                   " \"interfaces\": [{\"name\": \"root\", \"group\": \"clamp\", \"coupling\": \"rigid\"}],\n"
                   " \"reduction\": {\"method\": \"clamped\", \"interface\": \"root\", \"modes\": " +
                   std::to_string(modes) + "}}\n");
}

void write_shell_part(const fs::path& json, const fs::path& msh, const IsoMaterial& mat, double thickness, int modes) {
  std::ostringstream t;
  t.precision(17);
  t << thickness;
  write_file(json, "{\"comment\": \"reduce_bench: thin-walled tube of QUAD4 shells, clamped at x = 0\",\n"
                   " \"geometry\": \"" + msh.filename().string() + "\",\n"
                   " \"shells\": [{\"group\": \"skin\", \"thickness\": " + t.str() + ", " + material_fields(mat) + "}],\n"
                   " \"interfaces\": [{\"name\": \"root\", \"group\": \"clamp\", \"coupling\": \"rigid\"}],\n"
                   " \"reduction\": {\"method\": \"clamped\", \"interface\": \"root\", \"modes\": " +
                   std::to_string(modes) + "}}\n");
}

std::vector<std::pair<std::string, double>> read_stage_times(const fs::path& stderr_file) {
  std::vector<std::pair<std::string, double>> out;
  std::ifstream f(stderr_file);
  std::string line;
  const std::string prefix = "ffr-reduce:";
  while (std::getline(f, line)) {
    if (line.rfind(prefix, 0) != 0) continue;
    const std::string body = trim(line.substr(prefix.size()));
    const auto colon = body.find(':');
    if (colon == std::string::npos) continue;
    const std::string name = body.substr(0, colon);
    if (name == "timing") {
      // "timing: analyze 0.8 s, factorize 1.6 s, lanczos 6.1 s (78 solves), checks 0.4 s"
      std::istringstream items(body.substr(colon + 1));
      std::string item;
      while (std::getline(items, item, ',')) {
        std::istringstream w(item);
        std::string key;
        double v;
        if (w >> key >> v) out.emplace_back(key, v);
      }
      continue;
    }
    const auto open = body.rfind('[');
    if (open == std::string::npos || body.size() < 3 || body.compare(body.size() - 3, 3, " s]") != 0) continue;
    out.emplace_back(name, std::strtod(body.c_str() + open + 1, nullptr));
  }
  return out;
}

std::vector<double> read_sid_frequencies(const fs::path& sid) {
  formats::h5::Reader r(sid);
  return r.read_array("/refmod/frequency_hz", r.shape("/refmod/frequency_hz"));
}

double max_relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  const std::size_t n = std::min(a.size(), b.size());
  if (n == 0) return std::numeric_limits<double>::quiet_NaN();
  double m = 0;
  for (std::size_t i = 0; i < n; ++i) m = std::max(m, std::abs(a[i] / b[i] - 1.0));
  return m;
}

}  // namespace ffr::bench
