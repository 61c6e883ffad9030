// `corsa run --rig --format kitti` read back by a KITTI reader written from the devkit's format
// description (kitti_reader.h): the layout a KITTI loader expects, and images, calibration,
// labels and scans that agree (a LiDAR point of a labelled object projects into its 2D box, the
// 3D box's projection holds the 2D box).

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <string>

#include "kitti_reader.h"
#include "run_corsa.h"
#include "temp_dir.h"

namespace {

namespace fs = std::filesystem;
namespace kitti = corsa::test::kitti;

}  // namespace

TEST_CASE("A KITTI export loads as KITTI and its images match P2 and the scans",
          "[dataset][kitti]") {
  corsa::test::TempDir dir;
  const fs::path out = dir.path() / "k";
  const auto run = corsa::test::run_corsa(
      {"run", "scenarios/demo/cut_in_city.xosc", "--rig", "tests/collect/fixtures/kitti_rig.xml",
       "-o", out.string(), "--quiet", "--format", "kitti", "--duration", "4", "--npc",
       "vehicles=6,pedestrians=12", "--seed", "3"});
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  const fs::path root = out / "kitti";
  const auto train = kitti::read_image_set(root / "ImageSets/train.txt");
  const auto val = kitti::read_image_set(root / "ImageSets/val.txt");
  const auto all = kitti::read_image_set(root / "ImageSets/trainval.txt");
  CHECK(all.size() == 41);  // 4 s at 10 Hz, camera and LiDAR together
  CHECK(train.size() + val.size() == all.size());
  CHECK(train.size() == 33);  // the first 80%, by time
  CHECK(val.front() == "000033");

  size_t checked_objects = 0, points_in_boxes = 0, points_on_target = 0, dont_care = 0;
  for (const std::string& id : all) {
    INFO(id);
    const fs::path training = root / "training";
    REQUIRE(fs::exists(training / "image_2" / (id + ".png")));
    const auto labels = kitti::read_labels(training / "label_2" / (id + ".txt"));
    const auto calib = kitti::read_calib(training / "calib" / (id + ".txt"));
    const auto scan = kitti::read_velodyne(training / "velodyne" / (id + ".bin"));
    REQUIRE(!scan.empty());
    for (const kitti::Object& o : labels) {
      CHECK(o.box[0] >= 0.0);
      CHECK(o.box[2] <= 639.0);
      if (o.type == "DontCare") {
        ++dont_care;
        continue;
      }
      CHECK(o.box[3] - o.box[1] + 1 >= 25.0);  // smaller ones are DontCare
      // The 3D box's projection contains the tight 2D box (the object is inside its box).
      double u_min = 1e9, u_max = -1e9, v_min = 1e9, v_max = -1e9;
      bool in_front = true;
      for (const auto& c : kitti::corners(o)) {
        double u = 0, v = 0;
        in_front = in_front && kitti::project(calib, c, u, v);
        u_min = std::min(u_min, u);
        u_max = std::max(u_max, u);
        v_min = std::min(v_min, v);
        v_max = std::max(v_max, v);
      }
      if (!in_front || o.truncated > 0.05 || o.occluded > 0) {
        continue;
      }
      CHECK(o.box[0] >= u_min - 2.0);
      CHECK(o.box[2] <= u_max + 2.0);
      CHECK(o.box[1] >= v_min - 2.0);
      CHECK(o.box[3] <= v_max + 2.0);
      // Points of the scan inside the object's 3D box project into its 2D box: the rectified
      // image, P2 and Tr_velo_to_cam agree (with a distorted image they missed by up to the
      // lens's 10 px at the edges of this 640 px camera).
      size_t inside = 0, on_target = 0;
      for (const kitti::Point& p : scan) {
        const auto cam = kitti::velo_to_rect(calib, p);
        if (!kitti::inside(o, cam, -0.05)) {
          continue;
        }
        double u = 0, v = 0;
        if (!kitti::project(calib, cam, u, v)) {
          continue;
        }
        ++inside;
        on_target +=
            u >= o.box[0] - 1.5 && u <= o.box[2] + 1.5 && v >= o.box[1] - 1.5 && v <= o.box[3] + 1.5
                ? 1
                : 0;
      }
      if (inside >= 5) {
        ++checked_objects;
        points_in_boxes += inside;
        points_on_target += on_target;
      }
    }
  }
  CHECK(dont_care > 0);
  REQUIRE(checked_objects >= 10);
  CHECK(static_cast<double>(points_on_target) >= 0.98 * static_cast<double>(points_in_boxes));
}

TEST_CASE("KITTI DontCare thresholds come from the options", "[dataset][kitti]") {
  corsa::test::TempDir dir;
  const auto strict = corsa::test::run_corsa(
      {"run", "scenarios/demo/cut_in_city.xosc", "--rig", "tests/collect/fixtures/kitti_rig.xml",
       "-o", (dir.path() / "s").string(), "--quiet", "--format", "kitti", "--duration", "0.3",
       "--kitti-min-height", "1000"});
  INFO(strict.err);
  REQUIRE(strict.exit_code == 0);
  for (const char* id : {"000000", "000001", "000002", "000003"}) {
    for (const auto& o :
         kitti::read_labels(dir.path() / "s/kitti/training/label_2" / (std::string(id) + ".txt"))) {
      CHECK(o.type == "DontCare");  // nothing is 1000 px tall
    }
  }
  const auto no_kitti = corsa::test::run_corsa(
      {"run", "scenarios/demo/cut_in_city.xosc", "--rig", "tests/collect/fixtures/kitti_rig.xml",
       "-o", (dir.path() / "n").string(), "--kitti-max-distance", "50"});
  CHECK(no_kitti.exit_code == 2);
  CHECK_THAT(no_kitti.err, Catch::Contains("need --format kitti"));
}
