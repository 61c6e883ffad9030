// How person-like the rendered pedestrians are to a detector trained on photographs: OpenCV's
// HOG people detector (cv::HOGDescriptor::getDefaultPeopleDetector, Dalal and Triggs, trained on
// the INRIA person photographs) run on 1280 x 720 midday frames of a street (road, sidewalks,
// the bundled building district, parked and passing cars) with 3 to 5 pedestrians 6 to 12 m
// in front of the camera: walking in every direction at 0.8-1.7 m/s or standing, of every
// height, build and clothing the seeds give.
//
// A pedestrian counts when it is at least 100 px tall, unoccluded (occlusion < 10%) and not
// truncated. A detection matches it at IoU >= 0.5 against the tight box of its visible pixels
// after shrinking the detector's window as OpenCV's own people-detection sample does (the window
// has margins around the person: x + 10%, width 80%, y + 7%, height 80%). Unmatched detections
// are false positives. Printed: recall, false positives per frame, and the frames with
// detections drawn (when an output folder is given).
// Usage: corsa_bench_pedestrians [FRAMES] [OUT_DIR] [SEED]

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/objdetect.hpp>
#include <span>
#include <string>
#include <vector>

#include "corsa/core/random.h"
#include "corsa/sensors/camera_render.h"
#include "corsa/sensors/labels.h"
#include "corsa/sensors/model_io.h"
#include "street_mesh.h"

using namespace corsa::sensors;
using corsa::engine::EntityCategory;
using corsa::engine::EntitySnapshot;

namespace {

double iou(const cv::Rect2d& a, const cv::Rect2d& b) {
  const double inter = (a & b).area();
  return inter / (a.area() + b.area() - inter);
}

// The street with the bundled building district, for frame `f`'s seed.
Scene street_scene(uint64_t seed, int f) {
  SceneOptions options;
  options.origin = {100.0, 0.0, 0.0};
  options.seed = seed * 1000 + static_cast<uint64_t>(f);
  Scene scene(options);
  scene.add_road_mesh(corsa::bench::street_mesh(8.0, corsa::xodr::LaneType::kBorder));
  for (auto& m :
       load_model(std::string(CORSA_SOURCE_DIR) + "/scenarios/models/street_district.glb", {})) {
    scene.add_static_mesh(std::move(m));
  }
  scene.commit();
  return scene;
}

// The camera stands on the road looking along it, or across it towards a sidewalk.
Rigid camera_pose(corsa::RandomStream& rng) {
  const double yaw = rng.uniform01() < 0.5 ? 0.0 : (rng.uniform01() < 0.5 ? 0.5 : -0.5);
  return rigid_from_pose(40.0 + 40.0 * rng.uniform01(), rng.uniform(-4.0, 4.0), 1.5, yaw, 0.0, 0.0);
}

// 3 to 5 pedestrians 6 to 12 m in front of the camera `eye`, then three cars beyond them.
std::vector<EntitySnapshot> street_entities(corsa::RandomStream& rng, const Rigid& eye, int f) {
  std::vector<EntitySnapshot> entities;
  uint32_t id = 1;
  const int people = static_cast<int>(rng.uniform_int(3, 5));
  for (int p = 0; p < people; ++p) {
    EntitySnapshot e;
    e.instance_id = id++;
    e.name = "walker" + std::to_string(f) + "_" + std::to_string(p);
    e.category = EntityCategory::kPedestrian;
    const double distance = rng.uniform(6.0, 12.0);
    const double lateral = (p - 0.5 * (people - 1)) * 2.2 + rng.uniform(-0.4, 0.4);
    const Vec3 at = eye.apply({distance, lateral, -1.5});
    const double height = rng.uniform(1.55, 1.95);
    e.pose = {at.x, at.y, std::fabs(at.y) > 8.0 ? 0.15 : 0.0, rng.uniform(-M_PI, M_PI), 0.0, 0.0};
    e.box = {0.0, 0.0, 0.5 * height, 0.6, 0.6, height};
    e.speed = rng.uniform01() < 0.25 ? 0.0 : rng.uniform(0.8, 1.7);
    e.odometer = rng.uniform(0.0, 50.0);
    entities.push_back(e);
  }
  // Background traffic beyond the people.
  for (int c = 0; c < 3; ++c) {
    EntitySnapshot e;
    e.instance_id = id++;
    e.name = "car" + std::to_string(f) + "_" + std::to_string(c);
    e.category = EntityCategory::kCar;
    e.pose = {
        eye.translation.x + 20.0 + 9.0 * c, c % 2 ? 6.0 : -2.0, 0.0, c % 2 ? 0.0 : M_PI, 0.0, 0.0};
    e.box = {1.4, 0.0, 0.75, 4.6, 1.9, 1.5};
    entities.push_back(e);
  }
  return entities;
}

// The detector's windows on `bgr`, shrunk to the person inside as OpenCV's sample does.
std::vector<cv::Rect2d> detect_people(cv::HOGDescriptor& hog, const cv::Mat& bgr) {
  std::vector<cv::Rect> raw;
  hog.detectMultiScale(bgr, raw, 0.0, cv::Size(8, 8), cv::Size(16, 16), 1.05, 2.0);
  std::vector<cv::Rect2d> detections;
  for (const cv::Rect& r : raw) {
    detections.emplace_back(r.x + 0.1 * r.width, r.y + 0.07 * r.height, 0.8 * r.width,
                            0.8 * r.height);
  }
  return detections;
}

struct Tally {
  int counted = 0;          ///< pedestrians >= 100 px, unoccluded, not truncated
  int found = 0;            ///< of those, matched by a detection
  int false_positives = 0;  ///< detections matching no pedestrian
};

// Matches the detections to the frame's pedestrians (IoU >= 0.5, each detection once), counts
// into `tally` and draws on `bgr`: found green, missed red, false positives magenta.
void score(std::span<const ObjectLabel> labels, const std::vector<cv::Rect2d>& detections,
           cv::Mat& bgr, Tally& tally) {
  std::vector<bool> used(detections.size(), false);
  for (const ObjectLabel& l : labels) {
    if (l.semantic != SemanticClass::kPerson) {
      continue;
    }
    const cv::Rect2d truth(l.box_2d_visible.x_min, l.box_2d_visible.y_min,
                           l.box_2d_visible.x_max - l.box_2d_visible.x_min + 1.0,
                           l.box_2d_visible.y_max - l.box_2d_visible.y_min + 1.0);
    const bool eligible = truth.height >= 100.0 && l.occlusion < 0.1 && l.truncation == 0.0;
    int best = -1;
    double best_iou = 0.5;
    for (size_t i = 0; i < detections.size(); ++i) {
      const double v = iou(truth, detections[i]);
      if (!used[i] && v >= best_iou) {
        best = static_cast<int>(i);
        best_iou = v;
      }
    }
    if (best >= 0) {
      used[best] = true;  // a match (of any pedestrian) is not a false positive
    }
    if (eligible) {
      ++tally.counted;
      tally.found += best >= 0;
      cv::rectangle(bgr, truth, best >= 0 ? cv::Scalar(0, 200, 0) : cv::Scalar(0, 0, 255), 2);
    }
  }
  for (size_t i = 0; i < detections.size(); ++i) {
    if (!used[i]) {
      ++tally.false_positives;
      cv::rectangle(bgr, detections[i], cv::Scalar(255, 0, 255), 1);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  const int frames = argc > 1 ? std::max(1, std::atoi(argv[1])) : 40;
  const std::string out_dir = argc > 2 ? argv[2] : "";
  const uint64_t seed = argc > 3 ? std::strtoull(argv[3], nullptr, 10) : 7;
  if (!out_dir.empty()) {
    std::filesystem::create_directories(out_dir);
  }
  CameraIntrinsics k;
  k.width = 1280;
  k.height = 720;
  k.fov_deg = 90.0;
  const CameraRenderer camera(k);
  corsa::engine::EnvironmentState env;
  env.sun_azimuth = 2.4;  // afternoon sun from the south-south-west
  env.sun_elevation = 1.0;
  const Lighting noon = compute_lighting(env, {});
  cv::HOGDescriptor hog;
  hog.setSVMDetector(cv::HOGDescriptor::getDefaultPeopleDetector());
  corsa::RandomStream rng(seed);
  Tally tally;
  for (int f = 0; f < frames; ++f) {
    Scene scene = street_scene(seed, f);
    const Rigid eye = camera_pose(rng);
    scene.set_entities(street_entities(rng, eye, f));
    RenderSettings settings;
    settings.outputs.rgb = true;
    settings.lighting = &noon;
    settings.frame_seed = static_cast<uint64_t>(f) + 1;
    CameraMotion motion;
    motion.world_from_body = eye;
    const CameraImages img = camera.render(scene, motion, settings);
    const auto labels = camera_labels(scene, camera, eye, img.instance);
    cv::Mat rgb(k.height, k.width, CV_8UC3, const_cast<uint8_t*>(img.rgb.data()));
    cv::Mat bgr;
    cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
    score(labels, detect_people(hog, bgr), bgr, tally);
    if (!out_dir.empty()) {
      char name[64];
      std::snprintf(name, sizeof name, "/%03d.png", f);
      cv::imwrite(out_dir + name, bgr);
    }
  }
  std::printf(
      "HOG people detector on %d frames: %d of %d pedestrians (>= 100 px, unoccluded) "
      "found, recall %.1f %%; %.2f false positives per frame\n",
      frames, tally.found, tally.counted, tally.counted ? 100.0 * tally.found / tally.counted : 0.0,
      static_cast<double>(tally.false_positives) / frames);
  return 0;
}
