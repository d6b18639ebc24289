#pragma once
// Twin against measured (bench.md §5): the residual (measured − predicted TE: mean, RMS, p2p),
// the TE noise floor the sensors allow, and twin.csv in a run folder. Each point is taken as
// it comes, so a run of hours keeps none of them (issue #12).

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>

#include "wavebench/metrology/twin_calibration.hpp"
#include "wavebench/storage/atomic_file.hpp"
#include "wavebench/twin/twin_point.hpp"

namespace wavebench::twin {

// The figures of the points with both a measured and a predicted TE.
class TwinOverlaySum {
 public:
  void add(const TwinPoint& point);
  std::size_t overlapping() const { return overlapping_; }
  // Throws std::invalid_argument when fewer than 8 points overlap.
  metrology::TwinResidual residual() const { return residual_.result(); }
  // The white part of the residual from its third differences over consecutive samples
  // (Σ of the squared weights 1, 3, 3, 1 is 20): what no twin can predict [arcsec].
  double noise_floor_arcsec() const;

 private:
  metrology::TwinResidualSum residual_;
  std::size_t overlapping_ = 0;
  // The last four points' index and residual [rad], for the third differences.
  std::array<std::uint64_t, 4> index_{};
  std::array<double, 4> value_{};
  std::size_t seen_ = 0;
  double third_squares_ = 0;
  std::size_t thirds_ = 0;
};

// Throws std::invalid_argument when fewer than 8 points overlap.
metrology::TwinResidual twin_overlay_residual(std::span<const TwinPoint> points);

// twin.csv: t,index,measured_te_arcsec,predicted_te_arcsec,residual_arcsec; one row per point,
// an empty field where a value is missing. Appears whole at commit() (AtomicFileWriter).
class TwinCsvWriter {
 public:
  // Throws std::system_error naming the file.
  explicit TwinCsvWriter(const std::filesystem::path& file);
  void add(const TwinPoint& point);  // throws std::system_error when the disk refuses
  void commit();
  std::uint64_t rows() const { return rows_; }

 private:
  storage::AtomicFileWriter file_;
  std::uint64_t rows_ = 0;
};

void write_twin_csv(const std::filesystem::path& file, std::span<const TwinPoint> points);

}  // namespace wavebench::twin
