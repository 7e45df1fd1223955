#pragma once
// ffr-info's pieces: a JSON summary of each kind of file, and its text rendering.
#include "ffr/formats/h5.hpp"
#include "ffr/formats/results_io.hpp"
#include "ffr/formats/sid.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace ffr::info {

nlohmann::json summarize_sid(const formats::Sid& sid, const std::string& file, std::int64_t format_version);
nlohmann::json summarize_results(const formats::Results& r, const std::string& file);

/// Human-readable text of a summary made by one of the above.
std::string render_text(const nlohmann::json& summary);

/// `ffr-info FILE --campbell AXIS --speeds LIST [--json] [--png OUT]`.
int run_campbell(const std::filesystem::path& file, const std::string& axis, const std::string& speeds, bool json,
                 const std::string& png);

/// `ffr-info RESULTS.h5 --plot CH1,CH2[i],... --png OUT`: time histories, one panel per channel.
int run_plot(const std::filesystem::path& file, const std::string& channels, const std::string& png);

/// `ffr-info RESULTS.h5 --stress BODY [--model MODEL.json] [--json]` (stress_cmd.cpp).
int run_stress(const std::filesystem::path& run, const std::string& body, const std::string& model, bool json);

}  // namespace ffr::info
