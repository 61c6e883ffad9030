#pragma once

// Catalogs (§9.4): the eight CatalogLocations, and catalog documents. Scenario loading expands
// every CatalogReference itself; load_catalog reads a catalog file on its own (for validation),
// each entry with its declared default parameter values.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "corsa/core/diagnostic.h"
#include "corsa/xosc/common.h"
#include "corsa/xosc/entities.h"
#include "corsa/xosc/environment.h"
#include "corsa/xosc/storyboard.h"
#include "corsa/xosc/trajectories.h"

namespace corsa::xosc {

/// A catalog directory as written, and resolved against the scenario file's folder.
struct CatalogDirectory {
  std::string path;
  std::filesystem::path resolved;
  Source source;
};

struct CatalogLocations {
  std::optional<CatalogDirectory> vehicle;
  std::optional<CatalogDirectory> controller;
  std::optional<CatalogDirectory> pedestrian;
  std::optional<CatalogDirectory> misc_object;
  std::optional<CatalogDirectory> environment;
  std::optional<CatalogDirectory> maneuver;
  std::optional<CatalogDirectory> trajectory;
  std::optional<CatalogDirectory> route;
  Source source;
};

/// A catalog document: one Catalog element with entries of any of the eight kinds.
struct Catalog {
  FileHeader header;
  std::string name;
  std::vector<Vehicle> vehicles;
  std::vector<Controller> controllers;
  std::vector<Pedestrian> pedestrians;
  std::vector<MiscObject> misc_objects;
  std::vector<Environment> environments;
  std::vector<Maneuver> maneuvers;
  std::vector<Trajectory> trajectories;
  std::vector<Route> routes;
  Source source;
};

/// Reads and checks a catalog file. Throws InputError (file:line) on bad input; warnings go to
/// `diagnostics`.
Catalog load_catalog(const std::filesystem::path& path, Diagnostics& diagnostics);

}  // namespace corsa::xosc
