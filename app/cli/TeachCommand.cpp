// scanpick-cli teach: crop a part from a scan, find its features and write a .spmodel file.
#include "app/cli/CliCommon.h"
#include "app/cli/Commands.h"
#include "app/cli/RecipeOptions.h"
#include "app/cli/TeachTruth.h"
#include "core/ambiguity/ViewAmbiguities.h"
#include "core/common/AtomicFile.h"
#include "core/model/ModelFile.h"
#include "core/model/ViewCoverage.h"
#include "core/params/ParameterTable.h"
#include "core/sim/Mesh.h"
#include "core/sim/MeshIo.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <sstream>

namespace scanpick::cli {
namespace {

std::vector<double> parseNumbers(const std::string& text, std::size_t count,
                                 const std::string& what) {
  std::vector<double> values;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    try {
      values.push_back(std::stod(item));
    } catch (const std::exception&) {
      throw core::Error(what + ": '" + item + "' is not a number");
    }
  }
  if (values.size() != count)
    throw core::Error(what + ": expected " + std::to_string(count) +
                      " comma-separated numbers, got " + std::to_string(values.size()));
  return values;
}

/// A --grip value: NAME=x,y,z[,ax,ay,az[,cx,cy,cz]] (scan frame: position in mm, then the
/// approach and the fingers' closing axis as directions of any length).
core::GripPoint parseGrip(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw core::Error("--grip '" + text +
                      "': expected NAME=x,y,z[,ax,ay,az[,cx,cy,cz]] (scan frame, mm)");
  const std::string what = "--grip " + text.substr(0, eq);
  const std::string numbers = text.substr(eq + 1);
  const auto count = std::size_t(std::count(numbers.begin(), numbers.end(), ',') + 1);
  if (count != 3 && count != 6 && count != 9)
    throw core::Error(what +
                      ": expected 3 numbers (x,y,z), 6 (and the approach) or 9 (and the "
                      "closing axis), got " +
                      std::to_string(count));
  const auto v = parseNumbers(numbers, count, what);
  core::GripPoint grip{text.substr(0, eq), Eigen::Vector3d(v[0], v[1], v[2])};
  if (v.size() >= 6)
    grip.approach = Eigen::Vector3d(v[3], v[4], v[5]);
  if (v.size() == 9)
    grip.closing_axis = Eigen::Vector3d(v[6], v[7], v[8]);
  return core::checkedGrip(grip);
}

/// A mesh is sampled no denser than this many points (a large part more sparsely than the
/// sensor's spacing): enough for any part the sensor sees, and teach stays within seconds.
constexpr std::size_t kMaxMeshPoints = 150000;

/// The part's mesh (--mesh: its own frame, in `units`) as a cloud of its every side in front of
/// the teach camera, about the sensor's point spacing apart; teach fits the normals as for any
/// cloud (a mesh of overlapping solids has faces inside the part, whose normals would point into
/// it and break the outward orientation of the faces around them). `options`
/// gets the crop around it, the part's pose in it (T_scan_part, so that the model knows its place
/// in the part) and the grip points moved from the mesh frame into it.
core::PointCloud meshAsScan(const std::string& path, const std::string& units,
                            core::TeachOptions& options) {
  core::TriangleMesh mesh = core::loadMesh(path);
  const double scale = core::parseLengthUnit(units) == core::LengthUnit::Metres ? 1000.0 : 1.0;
  for (auto& v : mesh.vertices_mm)
    v *= scale;
  const double area_mm2 = core::surfaceArea(mesh);
  if (!(area_mm2 > 0))
    throw core::Error("--mesh " + path + " holds no surface: give the part's triangle mesh");
  const core::SensorModel& sensor = options.sensor;
  const double spacing_mm = sensor.fx > 0 ? sensor.nominal_distance_mm / sensor.fx : 0.5;
  const auto count = std::min(kMaxMeshPoints, std::size_t(area_mm2 / (spacing_mm * spacing_mm)));
  std::vector<Eigen::Vector3d> points, normals;
  core::sampleSurface(mesh, std::max<std::size_t>(count, core::kMinTeachPoints), 1, points,
                      normals);
  // In front of the camera, beyond the sensor's working distance by the part's size.
  const Eigen::AlignedBox3d box = core::boundingBox(mesh);
  const Eigen::Isometry3d T_scan_part(Eigen::Translation3d(
      Eigen::Vector3d(0, 0, sensor.nominal_distance_mm + box.diagonal().norm()) - box.center()));
  core::PointCloud cloud;
  for (const auto& p : points)
    cloud.points_mm.push_back((T_scan_part * p).cast<float>());
  cloud.width = static_cast<std::uint32_t>(cloud.points_mm.size());
  cloud.height = 1;
  options.T_scan_part = T_scan_part;
  for (auto& g : options.grips_scan)
    g = core::transformed(g, T_scan_part);
  const Eigen::AlignedBox3f crop = core::boundingBox(cloud);
  options.crop_box_mm = Eigen::AlignedBox3f(crop.min() - Eigen::Vector3f::Constant(1.0f),
                                            crop.max() + Eigen::Vector3f::Constant(1.0f));
  return cloud;
}

/// The teach scan: --scan's cloud, or --mesh's surface (meshAsScan).
core::PointCloud teachScan(const std::string& scan, const std::string& mesh,
                           const std::string& units, core::TeachOptions& options) {
  return mesh.empty() ? loadWithUnitsCheck(scan, units) : meshAsScan(mesh, units, options);
}

/// The measured scan and part, then each derived parameter with its reason (or that --set
/// replaced it).
void printDerived(const core::AutoParams& derived, const core::TaughtModel& model) {
  std::cout << "measured: point spacing " << derived.scan.spacing_mm << " mm, depth noise "
            << derived.scan.noise_mm << " mm, part diameter " << derived.part.diameter_mm << " mm ("
            << derived.part.extent_mm.x() << " x " << derived.part.extent_mm.y() << " x "
            << derived.part.extent_mm.z() << " mm), " << derived.part.points
            << " points\nparameters derived for this part (--set overrides any):\n";
  for (const auto& v : derived.values) {
    const auto reason = model.param_reasons.find(v.key);
    std::cout << "  " << v.key << " = " << core::findParameter(v.key)->get(model.params) << ": "
              << (reason != model.param_reasons.end() ? reason->second : "set by --set") << "\n";
  }
}

/// What the taught view (joined with the earlier views that share its part frame) leaves open,
/// analysed as recognition with the model's parameters does.
void printAmbiguities(const std::shared_ptr<const core::TaughtModel>& view) {
  std::cout << "what a scan of this view may leave open:\n";
  for (const auto& line :
       core::describeAmbiguities(core::analyzeViewAmbiguities(view, view->params)))
    std::cout << "  " << line << "\n";
}

/// The views given with --with-view, checked to be views of the part being taught (`name`).
std::vector<std::shared_ptr<const core::TaughtModel>>
earlierViews(const std::vector<std::string>& paths, const std::string& name) {
  std::vector<std::shared_ptr<const core::TaughtModel>> views;
  for (const auto& path : paths) {
    views.push_back(std::make_shared<const core::TaughtModel>(core::loadModel(path)));
    if (views.back()->name != name)
      throw core::Error("--with-view " + path + " is a view of '" + views.back()->name +
                        "', not of '" + name + "': give --name " + views.back()->name +
                        " to teach another view of that part");
  }
  return views;
}

} // namespace

void registerTeachCommand(CLI::App& app) {
  struct Options {
    RecipeOptions recipe;
    std::string scan, mesh, crop_box, crop_truth, part_pose, out, name = "part";
    bool remove_floor = false;
    std::vector<std::string> grips;
    std::vector<std::string> view_settings;
    std::vector<std::string> with_views;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub =
      addCommand(app, "teach", "Teach a part from a scan: crop, features, .spmodel", [o] {
        core::TeachOptions options;
        options.name = o->name;
        core::checkWritable(o->out);
        // The earlier views are read first: a bad one leaves no new model file behind.
        const auto views = earlierViews(o->with_views, o->name);
        options.remove_floor = o->remove_floor;
        options.source_units = core::parseLengthUnit(o->recipe.units);
        options.sensor =
            core::sensorPreset(o->recipe.sensor.empty() ? "phoxi-m-1032" : o->recipe.sensor);
        for (const auto& g : o->grips)
          options.grips_scan.push_back(parseGrip(g));
        if (o->scan.empty() == o->mesh.empty())
          throw core::Error("give exactly one of --scan or --mesh");
        if (!o->mesh.empty() && (!o->crop_box.empty() || !o->crop_truth.empty() ||
                                 !o->part_pose.empty() || o->remove_floor))
          throw core::Error("--mesh is the whole part in its own frame: give no crop, part "
                            "pose or floor removal with it");
        if (o->mesh.empty() && o->crop_box.empty() == o->crop_truth.empty())
          throw core::Error("give exactly one of --crop-box or --crop-from-truth");
        if (!o->crop_box.empty()) {
          const auto b = parseNumbers(o->crop_box, 6, "--crop-box");
          options.crop_box_mm =
              Eigen::AlignedBox3f(Eigen::Vector3f(float(b[0]), float(b[1]), float(b[2])),
                                  Eigen::Vector3f(float(b[3]), float(b[4]), float(b[5])));
          if (options.crop_box_mm->isEmpty())
            throw core::Error("--crop-box: each minimum must be below its maximum");
        } else if (!o->crop_truth.empty()) {
          teachOptionsFromTruth(o->crop_truth, options);
        }
        if (!o->part_pose.empty()) {
          try {
            options.T_scan_part = core::partPose(o->part_pose);
          } catch (const core::Error& e) {
            throw core::Error(std::string("--part-pose: ") + e.what());
          }
        }
        const core::PointCloud scan = teachScan(o->scan, o->mesh, o->recipe.units, options);
        // With no preset and no parameter file, every value is derived from the part and the
        // scan; --set still overrides any of them.
        const bool derive = o->recipe.preset.empty() && o->recipe.params.empty();
        core::AutoParams derived;
        if (derive)
          derived = core::autoTeachParams(scan, options);
        core::TaughtModel model =
            core::teach(scan, options, resolveParams(o->recipe, derived.params));
        for (const auto& v : derived.values)
          if (core::findParameter(v.key)->get(model.params) == v.value)
            model.param_reasons[v.key] = v.reason;
        model.teach_scan =
            std::filesystem::path(o->mesh.empty() ? o->scan : o->mesh).filename().string();
        for (const auto& kv : o->view_settings) {
          // Parsed and checked as --set is (an unknown key or a value out of range is an Error),
          // then kept as the table's number.
          const nlohmann::json setting = parseSetting(kv, "--view-set");
          const std::string key = setting.begin().key();
          const double value = core::findParameter(key)->get(core::paramsFromJson(setting));
          core::checkViewParam(key, value);
          model.view_params[key] = value;
        }
        core::saveModel(o->out, model);
        std::cout << "taught '" << model.name << "': " << model.cloud_mm.size() << " points, "
                  << model.keypoints_mm.size() << " keypoints, " << model.features.size()
                  << " features, diameter " << model.diameter_mm << " mm";
        for (const auto& [key, value] : model.view_params)
          std::cout << ", " << key << " = " << value << " for this view";
        std::cout << " -> " << o->out << "\n";
        if (model.all_around)
          std::cout << "the crop is the part seen from every side: its normals face out of it, and "
                       "it covers every viewing direction\n";
        if (derive)
          printDerived(derived, model);
        auto all_views = views;
        all_views.push_back(std::make_shared<const core::TaughtModel>(std::move(model)));
        printViewCoverage(core::viewCoverage(all_views));
        printAmbiguities(core::joinViews(all_views).back());
        return kOk;
      });
  sub->add_option("--scan", o->scan, "Scan holding the part (.pcd or .ply)");
  sub->add_option("--mesh", o->mesh,
                  "Instead of --scan: the part's triangle mesh (.ply, .stl, .obj, .vtk; a CAD "
                  "export, in --units), taught as the part seen from every side; --grip "
                  "positions are then in the mesh's frame");
  sub->add_option("--crop-box", o->crop_box,
                  "Crop box in the scan frame: xmin,ymin,zmin,xmax,ymax,zmax");
  sub->add_option(
      "--crop-from-truth", o->crop_truth,
      "Take the crop box, grip points and the part's pose from a teach scene's .gt.json");
  sub->add_option("--part-pose", o->part_pose,
                  "The part's pose in the scan frame, when known (a fixture, or the robot that "
                  "placed it): x,y,z (mm),qw,qx,qy,qz. Views taught knowing it are joined when "
                  "recognized together (overrides the pose of --crop-from-truth)");
  sub->add_flag("--remove-floor", o->remove_floor, "Remove the floor plane inside the crop");
  sub->add_option("--grip", o->grips,
                  "Grip point NAME=x,y,z[,ax,ay,az[,cx,cy,cz]] in the scan frame: position (mm), "
                  "then optionally the direction the gripper approaches it in and the axis "
                  "fingers close along (repeatable)");
  sub->add_option("--name", o->name, "Part name stored in the model")->capture_default_str();
  sub->add_option("--out", o->out, "Model file to write (.spmodel)")->required();
  sub->add_option("--with-view", o->with_views,
                  "An earlier view of this part (.spmodel, repeatable): the coverage printed "
                  "counts it with the new view");
  sub->add_option("--view-set", o->view_settings,
                  "A matching parameter this view sets for itself, KEY=VALUE (e.g. "
                  "matching.min_coverage=0.5 for a thin plate seen edge-on); stored in the model "
                  "and used in place of the recognition parameters' value; repeatable");
  o->recipe.add(sub);
}

} // namespace scanpick::cli
