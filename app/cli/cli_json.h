#pragma once
// JSON forms of core results shared by the CLI commands. nlohmann::json prints doubles with
// 17 significant digits when needed, so values round-trip exactly.
#include <optional>

#include <nlohmann/json.hpp>

#include "core/io/mesh/mesh_import.h"
#include "core/analysis/mesh_stats.h"

namespace sublift::cli {

/// Genus of an orientable manifold mesh ((2C - chi - loops) / 2); nullopt otherwise.
std::optional<long long> genus(const MeshStats& s);
nlohmann::json mesh_stats_json(const MeshStats& s);
nlohmann::json report_json(const ImportReport& r);

}  // namespace sublift::cli
