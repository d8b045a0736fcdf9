#pragma once
/// @file Synth.h
/// One simulated scan with ground truth: parts → physics → ray casting → files
/// (`PREFIX.pcd`, `PREFIX.png`, `PREFIX.gt.json`, see docs/file-formats.md "Ground truth").

#include "core/common/Progress.h"
#include "core/sim/Renderer.h"
#include "core/sim/Scene.h"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace scanpick::core {

/// What to simulate. Defaults give an 8-part PhoXi bin of supports.
struct SynthRequest {
  /// Built-in part names (builtInPartNames()); several make a mixed scene (round robin).
  std::vector<std::string> parts{"support"};
  std::filesystem::path mesh_path; ///< a mesh file (mm) instead of built-in parts when set
  bool close_holes = false;        ///< cap the mesh file's holes (closeHoles) before use
  LayoutKind layout = LayoutKind::Bin;
  int count = 8;                       ///< instances (teach: 1)
  std::string sensor = "phoxi-m-1032"; ///< sensorPresetNames()
  std::uint64_t seed = 0;
  std::optional<double>
      noise_sigma_mm;          ///< overrides the sensor's depth noise (SensorNoise::withSigma)
  bool noiseless = false;      ///< exact geometry (SensorNoise::none), for checks
  double camera_height_mm = 0; ///< 0 = default for the sensor and layout
  int teach_side = 0;          ///< teach layout: the side it rests on (SceneSpec)
  /// Teach layout: rest on the N-th most probable distinct resting pose instead (SceneSpec,
  /// core/sim/RestingPoses.h); teach_side must then be 0.
  std::optional<int> resting_side;
  BinGeometry bin; ///< bin layout: the bin's size
  /// Each instance's shape varies by up to this fraction (deformedPart: stretched, sheared and
  /// bent, like pears of one kind); 0 = every instance exactly as designed.
  double deformation = 0.0;
};

/// A simulated scan and everything needed for its ground truth.
struct SynthScene {
  /// The parts as designed (the ground truth's), whatever the deformation of their instances.
  std::vector<Part> parts;
  Scene scene;
  SensorModel sensor;
  SensorNoise noise;
  std::uint64_t seed = 0; ///< the request's seed
  RenderResult render;
};

/// Checks the request (sensor, parts, mesh, count, sides) and throws Error with what to fix, before
/// any work is done. Whether a resting side exists is known only once the part's resting poses
/// are computed: synthesize throws Error naming how many there are.
void validateRequest(const SynthRequest& request);

/// Builds and renders the scene (deterministic for a given request). Throws Error for bad input
/// (see validateRequest). Progress: physics 0-0.4, rendering 0.4-1.
SynthScene synthesize(const SynthRequest& request, const ProgressFn& progress = {});

/// The ground-truth JSON text (format "scanpick-ground-truth", version 1) naming the cloud and
/// picture files.
std::string groundTruthJson(const SynthScene& synth, const std::string& cloud_file,
                            const std::string& picture_file);

/// Writes PREFIX.pcd, PREFIX.png and PREFIX.gt.json (creating the folder). Everything is encoded
/// to temporary files first and renamed only when all three are complete, so a failure leaves no
/// scene file behind. Returns the three paths. Throws Error on failure.
std::vector<std::filesystem::path> writeSynthScene(const std::filesystem::path& prefix,
                                                   const SynthScene& synth);

} // namespace scanpick::core
