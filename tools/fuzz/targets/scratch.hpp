#pragma once
// A folder of the fuzzing process's own for the files its inputs become: the readers under test
// take paths (as the tools call them), so each input is written to a file and read back. On
// /dev/shm where there is one (memory, no disk traffic), else the system's temporary folder;
// removed when the process ends normally.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace ffr::fuzz {

/// The folder, created on first use.
const std::filesystem::path& scratch();

/// Writes `size` bytes to scratch()/name and returns the path.
std::filesystem::path write_scratch(const std::string& name, const std::uint8_t* data, std::size_t size);

}  // namespace ffr::fuzz
