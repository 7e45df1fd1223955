#pragma once
// The temporary names of AtomicFile (h5.hpp) and the removal of stale ones; also used for
// temporary folders of the same naming (ffr-sim --vtk's frames folder).
//
// A writer killed between creating its temporary file and renaming it (kill -9, a power cut)
// leaves the file behind. Every name is new (two writers of one target must not share one), so
// without a clean-up they would accumulate. The next AtomicFile of the same target removes
// those whose writer is gone: a temporary name carries the writer's host and process id, and a
// file is stale when it was written on this host and that process no longer exists, or exists
// but started after the file was last written (the id was reused by another process). A file of
// a live writer, or of another host sharing the folder, is never touched.
#include <filesystem>
#include <string>

namespace ffr::formats::h5::detail {

/// `.NAME.tmp-HOST-PID-HEX` next to `target` (HOST: this host's name, made safe for a file name).
std::filesystem::path temporary_name(const std::filesystem::path& target, unsigned long long random);

/// Removes the stale temporary files of `target`'s writers (see above); returns how many.
/// Errors (an unreadable folder, a file removed meanwhile) are ignored: the clean-up is a courtesy.
int remove_stale_temporaries(const std::filesystem::path& target);

/// The same for temporary folders named by temporary_name(target, ...) (not symbolic links):
/// each stale one is removed with its content; returns how many.
int remove_stale_temporary_folders(const std::filesystem::path& target);

/// Whether a temporary file named `name`, last written at `mtime_s` (seconds since the epoch),
/// is stale for this host (exposed for the tests).
bool is_stale_temporary(const std::string& target_filename, const std::string& name, double mtime_s);

}  // namespace ffr::formats::h5::detail
