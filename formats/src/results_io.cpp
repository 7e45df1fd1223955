#include "ffr/formats/results_io.hpp"

#include "ffr/version.hpp"

#include <cmath>
#include <stdexcept>

namespace ffr::formats {

const Results::Output* Results::find(const std::string& name) const {
  for (const auto& o : outputs)
    if (o.name == name) return &o;
  return nullptr;
}

void write_results(const Results& r, const std::filesystem::path& path) {
  const auto nt = static_cast<std::uint64_t>(r.time.size());
  if (!r.time.allFinite()) throw std::invalid_argument("results: non-finite time");
  if (r.stopped_at && !std::isfinite(*r.stopped_at)) throw std::invalid_argument("results: non-finite stopped_at");
  for (Eigen::Index i = 1; i < r.time.size(); ++i)
    if (r.time[i] < r.time[i - 1]) throw std::invalid_argument("results: time must be non-decreasing");
  for (const auto& o : r.outputs) {
    if (o.name.empty() || o.name.find('/') != std::string::npos)
      throw std::invalid_argument("results: bad output name '" + o.name + "'");
    if (static_cast<std::uint64_t>(o.values.rows()) != nt)
      throw std::invalid_argument("results: output '" + o.name + "' has " + std::to_string(o.values.rows()) +
                                  " rows for " + std::to_string(nt) + " times");
    if (!o.values.allFinite()) throw std::invalid_argument("results: output '" + o.name + "' has non-finite values");
  }
  h5::AtomicFile out(path);
  {
    h5::Writer w(out.temp_path(), path.string());
    w.attr("/", "format", std::string(kResultsFormatName));
    w.attr("/", "format_version", static_cast<std::int64_t>(kResultsFormatVersion));
    w.attr("/", "generator", r.generator.empty() ? std::string(kGenerator) : r.generator);
    w.attr("/", "steps", r.steps);
    w.attr("/", "newton_iterations", r.newton_iterations);
    w.attr("/", "integration_seconds", r.integration_seconds);
    if (r.stopped_at) {
      w.attr("/", "stopped_at", *r.stopped_at);
      w.attr("/", "stop_reason", r.stop_reason);
    }
    w.write("/time", r.time.data(), {nt});
    w.ensure_group("/outputs");
    for (const auto& o : r.outputs) {
      const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rm = o.values;
      const std::string p = "/outputs/" + o.name;
      w.write(p, rm.data(), {nt, static_cast<std::uint64_t>(o.values.cols())});
      if (!o.type.empty()) w.attr(p, "type", o.type);
    }
    w.close();
  }
  out.commit();
}

bool is_results_file(const h5::Reader& r) {
  if (r.has_attr("/", "format")) return r.attr_string("/", "format") == kResultsFormatName;
  return r.exists("/time") && r.is_group("/outputs");
}

Results read_results(const std::filesystem::path& path, std::vector<std::string>* warnings) {
  h5::Reader r(path);
  std::int64_t version = 0;
  if (r.has_attr("/", "format")) {
    const std::string f = r.attr_string("/", "format");
    if (f != kResultsFormatName) r.fail("/@format", "not an ffr-sim results file (format = '" + f + "')");
    version = r.attr_int("/", "format_version");
    if (version < 1 || version > kResultsFormatVersion)
      r.fail("/@format_version", "unsupported format_version " + std::to_string(version) + " (this build reads 1.." +
                                     std::to_string(kResultsFormatVersion) + ")");
  } else if (!is_results_file(r)) {
    r.fail("/@format", "missing attribute: not an ffr-sim results file");
  }
  if (version >= 2)
    r.require_checksums();
  else if (warnings)
    warnings->push_back(r.name() + ": " + (version ? "format_version " + std::to_string(version) : std::string("a file without format_version")) +
                        " has no content checksums: damage that HDF5 does not detect (a chunk index) cannot be found");
  Results res;
  if (r.has_attr("/", "generator")) res.generator = r.attr_string("/", "generator");
  const auto ts = r.shape("/time");
  if (ts.size() != 1) r.fail("/time", "wrong shape: expected rank 1, found " + h5::shape_string(ts));
  const auto t = r.read_array("/time", ts);
  res.time = Eigen::Map<const Eigen::VectorXd>(t.data(), static_cast<Eigen::Index>(t.size()));
  for (Eigen::Index i = 1; i < res.time.size(); ++i)
    if (res.time[i] < res.time[i - 1]) r.fail("/time", "times decrease at index " + std::to_string(i));
  res.steps = r.attr_int("/", "steps");
  res.newton_iterations = r.attr_int("/", "newton_iterations");
  res.integration_seconds = r.attr_double("/", "integration_seconds");
  if (r.has_attr("/", "stopped_at")) {
    res.stopped_at = r.attr_double("/", "stopped_at");
    if (r.has_attr("/", "stop_reason")) res.stop_reason = r.attr_string("/", "stop_reason");
  }
  if (!r.is_group("/outputs")) r.fail("/outputs", "missing group");
  for (const auto& name : r.members("/outputs")) {
    const std::string p = "/outputs/" + name;
    const auto s = r.shape(p);
    if (s.size() != 2 || s[0] != ts[0])
      r.fail(p, "wrong shape: expected [" + std::to_string(ts[0]) + ",k], found " + h5::shape_string(s));
    const auto v = r.read_array(p, s);
    Results::Output o;
    o.name = name;
    o.values = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
        v.data(), static_cast<Eigen::Index>(s[0]), static_cast<Eigen::Index>(s[1]));
    if (r.has_attr(p, "type")) o.type = r.attr_string(p, "type");
    res.outputs.push_back(std::move(o));
  }
  if (version >= 2) r.verify_content();
  return res;
}

}  // namespace ffr::formats
