// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The report of `strata bench` (QualityBench.h): report.csv (every row),
/// report.md (the presets, then every row) and pareto.png (time against
/// error, meshing and rendering).

#include <strata/bench/QualityBench.h>
#include <strata/render/Image.h>

#include <filesystem>
#include <string>

namespace strata::bench {

/// report.csv: one line per row; the scene rows have no geometric error.
std::string formatQualityCsv(const QualityBenchResult& result);

/// report.md.
std::string formatQualityMarkdown(const QualityBenchResult& result);

/// pareto.png: meshing time against mean shape error per configuration, and
/// the scene's render time against PSNR.
render::Image drawQualityPlot(const QualityBenchResult& result);

/// Writes DIR/report.csv, DIR/report.md and DIR/pareto.png (each
/// atomically) into the existing folder `dir`. Throws strata::Error (Io).
void writeQualityReport(const QualityBenchResult& result, const std::filesystem::path& dir);

} // namespace strata::bench
