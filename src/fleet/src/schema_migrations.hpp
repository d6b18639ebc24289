#pragma once
// The shared store's schema, as numbered migrations (docs/formats/fleet-store.md): migration N
// runs in one transaction with its row in schema_version, under an advisory lock, so benches
// starting at once apply each exactly once. After them, a step computed from the figure
// declarations adds the fleet_runs columns of newly declared trends (figure_columns.hpp).

#include "pg_connection.hpp"

namespace wavebench::fleet {

// Applies the migrations the database lacks; returns its version after.
int migrate_fleet_schema(PgConnection& db);
int fleet_schema_migrations();

}  // namespace wavebench::fleet
