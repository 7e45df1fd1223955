// Text rendering of the summaries (what ffr-info prints without --json).
#include "summary.hpp"

#include <cstdio>
#include <sstream>

namespace ffr::info {
namespace {

using nlohmann::json;

std::string num(const json& v) {
  if (v.is_null()) return "-";
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v.get<double>());
  return buf;
}

std::string row(const json& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + num(v[i]);
  return s + "]";
}

void line(std::ostringstream& o, const std::string& key, const std::string& value) {
  o << "  " << key << std::string(key.size() < 18 ? 18 - key.size() : 1, ' ') << value << "\n";
}

void matrix(std::ostringstream& o, const std::string& key, const json& m, const std::string& unit) {
  line(o, key, row(m[0]) + " " + unit);
  for (int r = 1; r < 3; ++r) line(o, "", row(m[r]));
}

void sid_text(std::ostringstream& o, const json& s) {
  o << s["file"].get<std::string>() << ": SID (ffr-sid version " << num(s["format_version"]) << ", written by "
    << s["provenance"]["generator"].get<std::string>() << ")\n";
  const auto& u = s["units"];
  line(o, "units", u["length"].get<std::string>() + ", " + u["mass"].get<std::string>() + ", " + u["time"].get<std::string>());
  line(o, "mass", num(s["mass"]) + " kg");
  line(o, "centre of mass", row(s["center_of_mass"]) + " m");
  matrix(o, "inertia about O", s["inertia_about_O"], "kg m^2");
  matrix(o, "inertia about CoM", s["inertia_about_com"], "kg m^2");
  line(o, "principal (CoM)", row(s["principal_moments_about_com"]) + " kg m^2");
  line(o, "reference", s["reference"].get<std::string>());
  line(o, "modes", num(s["nq"]));
  for (const auto& m : s["modes"]) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "mode %-4lld %12.6g Hz  %s", m["index"].get<long long>() + 1, m["frequency_hz"].get<double>(),
                  m["type"].get<std::string>().c_str());
    line(o, "", buf);
  }
  std::string nodes;
  for (const auto& n : s["nodes"]) nodes += (nodes.empty() ? "" : ", ") + n["name"].get<std::string>() + " " + row(n["origin"]);
  line(o, "nodes", nodes.empty() ? "(none)" : nodes);
  std::string itf;
  for (const auto& i : s["interfaces"])
    itf += (itf.empty() ? "" : ", ") + i["name"].get<std::string>() + " (node " + i["node"].get<std::string>() + ", " +
           i["coupling"].get<std::string>() + ")";
  line(o, "interfaces", itf.empty() ? "(none)" : itf);
  std::string st = s["stiffening"]["present"].get<bool>() ? "yes" : "no";
  if (s["stiffening"].contains("interfaces") && !s["stiffening"]["interfaces"].empty()) {
    st += " (interfaces";
    for (const auto& n : s["stiffening"]["interfaces"]) {
      st += ' ';
      st += n.get<std::string>();
    }
    st += ")";
  }
  if (s["stiffening"].value("Ke_M1", false)) st += ", second-order stiffness Ke/M1";
  line(o, "stiffening", st);
  line(o, "visual", s["visual"].is_null() ? "no" : num(s["visual"]["vertices"]) + " vertices, " + num(s["visual"]["triangles"]) + " triangles");
  if (s.contains("stress"))
    line(o, "stress",
         s["stress"].is_null()
             ? "no"
             : num(s["stress"]["nodes"]) + " nodes" +
                   (s["stress"].value("rows", s["stress"]["nodes"]) != s["stress"]["nodes"]
                        ? ", " + num(s["stress"]["rows"]) + " rows with the shells' top, middle and bottom"
                        : std::string()) +
                   " (" + s["stress"]["selection"].get<std::string>() + ")");
  o << "  provenance\n";
  for (const auto& [k, v] : s["provenance"].items()) {
    if (v.is_string()) {
      if (!v.get<std::string>().empty()) line(o, "  " + k, v.get<std::string>());
    } else if (!v.empty()) {
      std::string t;
      for (const auto& [kk, vv] : v.items()) t += (t.empty() ? "" : ", ") + kk + "=" + (vv.is_string() ? vv.get<std::string>() : num(vv));
      line(o, "  " + k, t);
    }
  }
  const auto& val = s["validation"];
  std::string head = val["ok"].get<bool>() ? "OK: all " + num(val["applicable"]) + " applicable checks pass"
                                          : "FAILED: " + num(val["failures"]) + " of " + num(val["applicable"]) + " checks";
  if (val.contains("worst")) head += " (largest " + val["worst"]["name"].get<std::string>() + ": rel " + num(val["worst"]["rel"]) + ")";
  line(o, "validation", head);
  for (const auto& c : val["failed"])
    line(o, "", "FAIL " + c["name"].get<std::string>() + ": rel " + num(c["rel"]) + " > tol " + num(c["tol"]) +
                    (c["note"].get<std::string>().empty() ? "" : " (" + c["note"].get<std::string>() + ")"));
}

void results_text(std::ostringstream& o, const json& r) {
  o << r["file"].get<std::string>() << ": ffr-sim results";
  if (!r["generator"].get<std::string>().empty()) o << " (written by " << r["generator"].get<std::string>() << ")";
  o << "\n";
  line(o, "time", num(r["time"]["start"]) + " .. " + num(r["time"]["end"]) + " s, " + num(r["time"]["samples"]) + " samples");
  if (!r["complete"].get<bool>())
    line(o, "stopped", "at t = " + num(r["stopped_at"]) + " s, before its end: " + r["stop_reason"].get<std::string>());
  line(o, "steps", num(r["steps"]));
  line(o, "newton iterations", num(r["newton_iterations"]));
  line(o, "integration", num(r["integration_seconds"]) + " s");
  line(o, "outputs", std::to_string(r["outputs"].size()));
  for (const auto& c : r["outputs"]) {
    std::string t = c["name"].get<std::string>() + " [" + num(c["shape"][0]) + "," + num(c["shape"][1]) + "]";
    if (!c["type"].get<std::string>().empty()) {
      t += ' ';
      t += c["type"].get<std::string>();
    }
    line(o, "", t);
    line(o, "", "  final " + row(c["final"]));
    if (c.contains("min")) line(o, "", "  range " + row(c["min"]) + " .. " + row(c["max"]));
  }
}

}  // namespace

std::string render_text(const json& summary) {
  std::ostringstream o;
  if (summary["kind"] == "sid")
    sid_text(o, summary);
  else
    results_text(o, summary);
  return o.str();
}

}  // namespace ffr::info
