#pragma once
// ffr-info's exports of a SID for other tools: the SID_FEM text file of a flexible body
// (--export-fbi) and the reduced matrices as Matrix Market files (--export-mtx). Layouts in
// formats/SPEC.md, "Exports".
#include <string>

namespace ffr::info {

/// Writes `out` (atomically: nothing on failure). Returns the exit status; throws
/// formats::FormatError for a SID that cannot be read or fails validation.
int run_export_fbi(const std::string& sid_file, const std::string& out);

/// Writes Me.mtx, Ke.mtx, De.mtx (and KeM1_<k>.mtx where the SID has Ke.M1) into the folder
/// `dir` (created if missing). Returns the exit status; throws as run_export_fbi.
int run_export_mtx(const std::string& sid_file, const std::string& dir);

}  // namespace ffr::info
