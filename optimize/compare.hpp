// `pronk compare`: tuned designs (design.json of `pronk optimize` or `pronk design`) run side
// by side on the same trials. Each design is read and checked as `pronk reproduce` reads it
// (optimize/design_reader.hpp) and evaluated by the reproduce machinery (evaluate_design) on a
// study of its own: its own scene, parameters and parameter values, with the trials (the
// scenarios and the validation set), the objective, the constraints, the stability setting
// and the fall penalty of the reference design's study (the first design's by default), in
// its own study's model or, with a model given, in that one. That model is set as a study
// stage sets it (the study's "model"), so a parameter, a robot perturbation or a metric the
// model ignores is refused as a stage refuses it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "optimize/design_reader.hpp"
#include "optimize/progress.hpp"
#include "optimize/reproduce.hpp"
#include "optimize/study.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::optimize {

struct CompareOptions {
  int threads = 1;
  /// "": every design in its own study's model; else impulse, pulse or pseudo_rigid for all.
  std::string model;
  /// The design (1-based) whose study's trials, objective and constraints every design runs.
  int reference = 1;
  /// > 0: the reference study's validation set draws this many random trials.
  long trials = 0;
  /// Given: the reference study's validation set draws its random trials from this seed.
  std::optional<std::uint64_t> seed;
  /// The trial every design plays back: "nominal" (the scene undisturbed, the nominal robot,
  /// as long as a validation trial), "scenarios:I" or "validation:I" (trial I of that set).
  std::string play = "nominal";
  /// Scene overrides ("/pointer=value") every design's scene takes after its study's own
  /// scene_overrides (e.g. MuJoCo's step: /mujoco={"timestep": 2.5e-4}).
  std::vector<std::string> scene_overrides;
  ProgressStyle progress = ProgressStyle::kOff;
  /// Throws io::InputError naming the option (or "command line" for fewer than two designs)
  /// for `designs` design files.
  void validate(size_t designs) const;
};

struct ComparedDesign {
  std::string file;             ///< its design.json, as given
  std::string label;            ///< its column: the design's directory name, made unique
  RecordedDesign recorded;      ///< as read and checked (its own study)
  Study judged;                 ///< the study it ran here: its scene and parameters, the trials
  bool own_study = false;       ///< `judged` is its own study (same trials, objective, model)
  DesignEvaluation evaluation;  ///< at its recorded optimizer coordinates
};

/// The trial played back: set "nominal" (index -1), "scenarios" or "validation".
struct PlaybackTrial {
  std::string set = "nominal";
  long index = -1;
  std::string name = "nominal";
};

struct Comparison {
  std::string reference_file;   ///< the design whose study's trials every design ran
  std::string reference_study;  ///< its study's name
  std::string model;            ///< CompareOptions::model
  std::vector<ComparedDesign> designs;
  PlaybackTrial playback;
  std::vector<std::string> notes;  ///< what a reader must know (models differ, ...)
};

/// Reads, checks and evaluates every design. Throws io::InputError for a missing or bad
/// design file (naming the file and the JSON Pointer), a design whose parameters or the
/// reference's trials its model ignores, or bad options.
Comparison compare_designs(const std::vector<std::string>& files, const CompareOptions& options);

/// The scene design `k` runs in the playback trial (its parameters bound, in its model, the
/// trial applied). Throws io::InputError when its parameters make no valid scene there.
scene::Scene playback_scene(const Comparison& c, size_t k);

/// A column name from a design file's path: its directory's name (or the file's stem), with
/// every character outside [A-Za-z0-9_.-] made '_'.
std::string design_label(const std::string& file);

}  // namespace pronk::optimize
