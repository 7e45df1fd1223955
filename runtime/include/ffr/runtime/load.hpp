#pragma once
// Building a Model from the model file (runtime/MODEL_FILE.md) and the SID files it names.

#include "ffr/formats/sid.hpp"
#include "ffr/runtime/model.hpp"

#include <filesystem>
#include <optional>
#include <string>

namespace ffr::runtime {

/// Reads and validates the model file and every SID it names; returns the finalised model.
/// Throws ModelError naming the file and the field on any bad input.
Model load_model(const std::filesystem::path& path);

/// Same from JSON text; relative paths are resolved against base_dir, `name` is used in messages.
Model parse_model(const std::string& text, const std::filesystem::path& base_dir, const std::string& name);

/// A rigid body from its mass, centre of mass and inertia about the centre of mass (global
/// axes), with its frame at `position` with `orientation` (columns: frame axes, global).
/// `where` names the input for error messages ("model.json", "bodies[0]").
Body make_rigid_body(const std::string& name, double mass, const Vector3d& com, const Matrix3d& inertia,
                     const Vector3d& position, const Matrix3d& orientation, const std::string& file,
                     const std::string& field);

/// A flexible body from a SID: the primitive integrals, the rotary parts, Ke, De (plus modal
/// damping of the given ratio), the stiffening terms when present and wanted, and the nodes.
/// Errors name `file` (the SID file) and say where the model refers to it (`field`).
Body make_flexible_body(const std::string& name, const formats::Sid& sid, const Vector3d& position,
                        const Matrix3d& orientation, std::optional<double> damping_ratio, bool stiffening,
                        const std::string& file, const std::string& field, std::vector<std::string>* notes = nullptr);

}  // namespace ffr::runtime
