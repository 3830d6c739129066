// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The report of `strata bench mesh` (MeshBench.h): mesh-bench.md and
/// mesh-bench.csv.

#include <strata/bench/MeshBench.h>

#include <string>

namespace strata::bench {

/// mesh-bench.md: the accuracy table, then the throughput table.
std::string formatMeshBenchMarkdown(const MeshBenchResult& result);

/// mesh-bench.csv: the rows, a blank line, then the throughput rows.
std::string formatMeshBenchCsv(const MeshBenchResult& result);

} // namespace strata::bench
