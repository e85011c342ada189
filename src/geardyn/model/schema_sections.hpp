#pragma once
// The sections of the model file's declaration table, one function each (schema_rotor.cpp,
// schema_solids.cpp, schema_gears.cpp); schema_model.cpp puts them under the root with the
// analysis types. Internal to the model module.
#include <string>
#include <vector>

#include "geardyn/model/schema.hpp"
#include "geardyn/model/schema_builder.hpp"

namespace geardyn::model {

// Gear types of [[gear_meshes]] and [[gear_pairs]] (`type` choices) and the groups some keys
// are restricted to.
inline const std::vector<std::string> kGearTypes = {"spur", "helical", "straight_bevel",
                                                    "spiral_bevel", "hypoid"};
inline const std::vector<std::string> kHelical = {"helical", "spiral_bevel", "hypoid"};
inline const std::vector<std::string> kBevel = {"straight_bevel", "spiral_bevel", "hypoid"};

/// The fields of several lists, in order.
std::vector<Field> join_fields(std::vector<std::vector<Field>> parts);

/// A `dofs` key (the model's, a shaft's): one of kDofSetNames, with `help` and what the values
/// mean; the caller adds the default and the setter.
keys::F dof_set_key(const std::string& help);

Section materials_section();
Section shafts_section();
Section nodes_section();
Section disks_section();
Section point_masses_section();
Section bearings_section();
Section couplings_section();
Section gear_meshes_section();
Section constraints_section();
Section unbalances_section();
Section forces_section();
Section sensors_section();
Section damping_section();
Section solids_section();
Section gear_pairs_section();
// The nonlinear drivetrain (schema_drivetrain.cpp).
Section contacts_section();
Section bolts_section();
Section bushings_section();
Section rolling_bearings_section();
Section drivers_section();
Section loads_section();
Section clutches_section();
Section virtual_sensors_section();
Section mesh_contact_section();  ///< [gear_meshes.contact], a sub-table of [[gear_meshes]]
/// [nonlinear_elements.law] (schema_drivetrain.cpp: the contact laws' keys).
Section nonlinear_contact_law_section();
// Harmonic balance (schema_nonlinear.cpp).
Section nonlinear_elements_section();

}  // namespace geardyn::model
