#include "avar/kinematics/urdf_visuals.hpp"

#include <tinyxml.h>
#include <urdf_parser/urdf_parser.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>

#include "avar/core/input_error.hpp"

namespace avar::kinematics {
namespace {

namespace fs = std::filesystem;

Eigen::Isometry3d isometry_of(const urdf::Pose& pose) {
  Eigen::Isometry3d t(Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z).normalized());
  t.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return t;
}

/// `package://NAME/REST`: REST inside the nearest folder called NAME at or above `folder`, or
/// beside one of them; the URDF's folder when none is found.
std::string resolve_package(std::string_view name_and_rest, const fs::path& folder) {
  const std::size_t slash = name_and_rest.find('/');
  const std::string name(name_and_rest.substr(0, slash));
  const std::string rest(slash == std::string_view::npos ? "" : name_and_rest.substr(slash + 1));
  std::error_code ignored;
  for (fs::path dir = fs::absolute(folder, ignored); !dir.empty(); dir = dir.parent_path()) {
    if (dir.filename() == name) return (dir / rest).string();
    if (fs::is_directory(dir / name, ignored)) return (dir / name / rest).string();
    if (dir == dir.parent_path()) break;
  }
  return (folder / rest).string();
}

std::string resolve_mesh(const std::string& written, const fs::path& folder) {
  constexpr std::string_view kPackage = "package://", kFile = "file://";
  const std::string_view w = written;
  if (w.substr(0, kPackage.size()) == kPackage) return resolve_package(w.substr(kPackage.size()), folder);
  if (w.substr(0, kFile.size()) == kFile) return std::string(w.substr(kFile.size()));
  const fs::path p(written);
  return p.is_absolute() ? written : (folder / p).string();
}

LinkVisual visual_of(const urdf::Link& link, const urdf::Visual& v, const urdf::ModelInterface& model, const fs::path& folder) {
  LinkVisual out;
  out.link = link.name;
  if (link.parent_joint) out.joint = link.parent_joint->name;
  out.origin = isometry_of(v.origin);
  switch (v.geometry->type) {
    case urdf::Geometry::BOX: {
      const auto& box = static_cast<const urdf::Box&>(*v.geometry);
      out.shape = VisualShape::box;
      out.size = Eigen::Vector3d(box.dim.x, box.dim.y, box.dim.z);
      break;
    }
    case urdf::Geometry::CYLINDER: {
      const auto& cylinder = static_cast<const urdf::Cylinder&>(*v.geometry);
      out.shape = VisualShape::cylinder;
      out.size = Eigen::Vector3d(cylinder.radius, cylinder.length, 0);
      break;
    }
    case urdf::Geometry::SPHERE:
      out.shape = VisualShape::sphere;
      out.size = Eigen::Vector3d(static_cast<const urdf::Sphere&>(*v.geometry).radius, 0, 0);
      break;
    case urdf::Geometry::MESH: {
      const auto& mesh = static_cast<const urdf::Mesh&>(*v.geometry);
      out.shape = VisualShape::mesh;
      out.mesh = mesh.filename;
      out.mesh_path = resolve_mesh(mesh.filename, folder);
      out.scale = Eigen::Vector3d(mesh.scale.x, mesh.scale.y, mesh.scale.z);
      break;
    }
  }
  // A material is given inline, or by name from the robot's top-level materials.
  urdf::MaterialSharedPtr material = v.material;
  if (!material && !v.material_name.empty()) material = model.getMaterial(v.material_name);
  if (material && material->texture_filename.empty())
    out.rgba = std::array<double, 4>{material->color.r, material->color.g, material->color.b, material->color.a};
  return out;
}

}  // namespace

std::vector<LinkVisual> visuals_from_urdf_text(const std::string& text, const std::string& file, const std::string& folder) {
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(text);
  if (!model) throw InputError({file, 0, 0}, "urdfdom refused the robot description; expected a valid URDF");
  // urdfdom keeps links by name; the document's order (TinyXML's, which urdfdom reads with)
  // reads better.
  TiXmlDocument document;
  document.Parse(text.c_str());
  std::vector<LinkVisual> visuals;
  const TiXmlElement* robot = document.RootElement();
  if (!robot) return visuals;
  for (const TiXmlElement* e = robot->FirstChildElement("link"); e; e = e->NextSiblingElement("link")) {
    const char* name = e->Attribute("name");
    const urdf::LinkConstSharedPtr link = name ? model->getLink(name) : nullptr;
    if (!link) continue;
    for (const urdf::VisualSharedPtr& v : link->visual_array)
      if (v && v->geometry) visuals.push_back(visual_of(*link, *v, *model, folder));
  }
  return visuals;
}

std::vector<LinkVisual> visuals_from_urdf_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError({path, 0, 0}, "cannot open the file; expected a readable URDF file");
  std::ostringstream text;
  text << in.rdbuf();
  return visuals_from_urdf_text(text.str(), path, fs::path(path).parent_path().string());
}

}  // namespace avar::kinematics
