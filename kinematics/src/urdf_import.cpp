#include "avar/kinematics/urdf_import.hpp"

#include <tinyxml.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>

#include "avar/core/format.hpp"
#include "avar/core/utf8.hpp"
#include "avar/kinematics/model_builder.hpp"

namespace avar::kinematics {
namespace {

struct JointElement {
  const TiXmlElement* element = nullptr;
  std::string name, type, parent, child;
};

class Checker {
 public:
  explicit Checker(std::string file) : file_(std::move(file)) {}

  SourceLocation at(const TiXmlNode* node) const { return {file_, node->Row(), node->Column()}; }

  [[noreturn]] void fail(const TiXmlNode* node, const std::string& problem) const { throw InputError(at(node), problem); }

  /// Checks the joints and links (with the lines urdfdom cannot give) and returns each joint's place.
  std::map<std::string, SourceLocation> check(const TiXmlElement& robot) {
    std::set<std::string> links;
    for (const TiXmlElement* link = robot.FirstChildElement("link"); link; link = link->NextSiblingElement("link")) {
      const char* name = link->Attribute("name");
      if (!name || !*name) fail(link, "found a <link> without a name; expected name=\"...\"");
      links.insert(name);
    }
    std::vector<JointElement> joints;
    std::map<std::string, const JointElement*> parent_joint_of_link;
    for (const TiXmlElement* e = robot.FirstChildElement("joint"); e; e = e->NextSiblingElement("joint")) joints.push_back(joint(e));
    std::map<std::string, SourceLocation> places;
    for (const JointElement& j : joints) {
      for (const std::string* link : {&j.parent, &j.child})
        if (!links.count(*link))
          fail(j.element, "joint '" + j.name + "' names link '" + *link + "', which is not declared; expected a <link name=\"" +
                              *link + "\">");
      if (const auto other = parent_joint_of_link.find(j.child); other != parent_joint_of_link.end())
        fail(j.element, "joint '" + j.name + "' gives link '" + j.child + "' a second parent (joint '" + other->second->name +
                            "' at line " + std::to_string(other->second->element->Row()) +
                            " is the first); expected a tree, each link the child of at most one joint");
      parent_joint_of_link[j.child] = &j;
      if (!places.emplace(j.name, at(j.element)).second)
        fail(j.element, "joint name '" + j.name + "' is used twice; expected unique joint names");
    }
    // Walking up from every joint must end at a root link; coming back to the start is a cycle.
    for (const JointElement& j : joints) {
      std::string link = j.parent;
      for (std::size_t steps = 0; steps <= joints.size(); ++steps) {
        const auto up = parent_joint_of_link.find(link);
        if (up == parent_joint_of_link.end()) break;
        if (up->second == &j)
          fail(j.element, "joint '" + j.name + "' closes a cycle through link '" + j.parent +
                              "'; expected a tree (no chain of joints leads back to its own link)");
        link = up->second->parent;
      }
    }
    std::vector<std::string> roots;
    for (const std::string& link : links)
      if (!parent_joint_of_link.count(link)) roots.push_back(link);
    if (roots.size() > 1)
      fail(&robot, "found " + std::to_string(roots.size()) + " root links ('" + roots[0] + "', '" + roots[1] +
                       "', ...); expected one link that is the child of no joint, every other link joined to it");
    return places;
  }

 private:
  JointElement joint(const TiXmlElement* e) const {
    JointElement j;
    j.element = e;
    const char* name = e->Attribute("name");
    if (!name || !*name) fail(e, "found a <joint> without a name; expected name=\"...\"");
    j.name = name;
    const char* type = e->Attribute("type");
    j.type = type ? type : "";
    const std::string who = "joint '" + j.name + "'";
    if (j.type != "revolute" && j.type != "continuous" && j.type != "prismatic" && j.type != "fixed")
      fail(e, who + " has " + (type ? "type '" + j.type + "'" : std::string("no type")) +
                  "; expected type=\"revolute\", \"continuous\", \"prismatic\" or \"fixed\"");
    j.parent = link_of(e, "parent", who);
    j.child = link_of(e, "child", who);
    if (j.type == "revolute" || j.type == "prismatic") {
      const TiXmlElement* limit = e->FirstChildElement("limit");
      double lower = 0, upper = 0;
      if (!limit || limit->QueryDoubleAttribute("lower", &lower) != TIXML_SUCCESS ||
          limit->QueryDoubleAttribute("upper", &upper) != TIXML_SUCCESS)
        fail(limit ? limit : e, who + " (" + j.type + ") has no limits; expected <limit lower=\"...\" upper=\"...\"" +
                                    (j.type == "revolute" ? " (rad)" : " (m)") + " effort=\"...\" velocity=\"...\"/>");
      if (!std::isfinite(lower) || !std::isfinite(upper) || lower > upper)
        fail(limit, who + " has limits lower " + format_number(lower) + ", upper " + format_number(upper) +
                        "; expected finite limits with lower <= upper");
    }
    if (const TiXmlElement* axis = e->FirstChildElement("axis"); axis && j.type != "fixed") {
      const char* xyz = axis->Attribute("xyz");
      std::istringstream in(xyz ? xyz : "");
      double x = 0, y = 0, z = 0;
      if (!(in >> x >> y >> z)) fail(axis, who + " has axis xyz=\"" + (xyz ? xyz : "") + "\"; expected three numbers");
      if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z) || std::sqrt(x * x + y * y + z * z) < 1e-12)
        fail(axis, who + " has axis (" + format_number(x) + ", " + format_number(y) + ", " + format_number(z) +
                       "); expected a non-zero finite direction");
    }
    return j;
  }

  std::string link_of(const TiXmlElement* e, const char* tag, const std::string& who) const {
    const TiXmlElement* element = e->FirstChildElement(tag);
    const char* link = element ? element->Attribute("link") : nullptr;
    if (!link || !*link) fail(element ? element : e, who + " has no " + tag + " link; expected <" + tag + " link=\"...\"/>");
    return link;
  }

  std::string file_;
};

Eigen::Isometry3d isometry(const urdf::Pose& pose) {
  Eigen::Isometry3d t(Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z).normalized());
  t.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return t;
}

JointSpec spec_of(const urdf::Joint& joint, const std::string& parent_joint) {
  JointSpec spec;
  spec.name = joint.name;
  spec.parent = parent_joint;
  spec.origin = isometry(joint.parent_to_joint_origin_transform);
  spec.axis = Eigen::Vector3d(joint.axis.x, joint.axis.y, joint.axis.z);
  switch (joint.type) {
    case urdf::Joint::CONTINUOUS:
      spec.type = JointType::revolute;
      spec.lower = -2 * std::numbers::pi;
      spec.upper = 2 * std::numbers::pi;
      break;
    case urdf::Joint::PRISMATIC:
    case urdf::Joint::REVOLUTE:
      spec.type = joint.type == urdf::Joint::REVOLUTE ? JointType::revolute : JointType::prismatic;
      spec.lower = joint.limits->lower;
      spec.upper = joint.limits->upper;
      break;
    default:
      spec.type = JointType::fixed;
      break;
  }
  return spec;
}

/// Adds the joints below `link`, depth first, parents before children.
void add_below(const urdf::Link& link, const std::string& parent_joint, ModelBuilder& builder,
               const std::map<std::string, SourceLocation>& places) {
  for (const urdf::JointSharedPtr& joint : link.child_joints) {
    builder.add_joint(spec_of(*joint, parent_joint), places.at(joint->name));
    builder.add_effector({joint->child_link_name, joint->name, Eigen::Isometry3d::Identity()}, places.at(joint->name));
  }
  for (const urdf::LinkSharedPtr& child : link.child_links) add_below(*child, child->parent_joint->name, builder, places);
}

/// TinyXML trusts its text: a multi-byte sequence cut short makes it read past the end, and a NUL
/// ends the document early. Both are refused first, located.
void check_urdf_characters(const std::string& text, const std::string& file) {
  const std::size_t nul = text.find('\0');
  const std::optional<std::size_t> bad = first_invalid_utf8(text);
  if (nul == std::string::npos && !bad) return;
  const std::size_t at = bad ? std::min(*bad, nul) : nul;
  throw InputError(location_at(file, text, at),
                   at == nul ? "found a NUL byte; expected XML text" : "found a byte that is not UTF-8; expected UTF-8 XML text");
}

}  // namespace

Model model_from_urdf_text(const std::string& text, const std::string& file) {
  check_urdf_characters(text, file);
  TiXmlDocument document;
  document.Parse(text.c_str());
  if (document.Error())
    throw InputError({file, document.ErrorRow(), document.ErrorCol()},
                     std::string("not well-formed XML (") + document.ErrorDesc() + "); expected a URDF document");
  const TiXmlElement* robot = document.RootElement();
  if (!robot || robot->ValueStr() != "robot")
    throw InputError({file, robot ? robot->Row() : 0, robot ? robot->Column() : 0},
                     "expected a <robot> element at the top of the URDF document");
  Checker checker(file);
  const std::map<std::string, SourceLocation> places = checker.check(*robot);

  const urdf::ModelInterfaceSharedPtr urdf_model = urdf::parseURDF(text);
  if (!urdf_model || !urdf_model->getRoot())
    throw InputError(checker.at(robot), "urdfdom refused the robot description (its message is on the console); expected a valid URDF");
  ModelBuilder builder;
  add_below(*urdf_model->getRoot(), std::string(), builder, places);
  return builder.build();
}

Model model_from_urdf_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError({path, 0, 0}, "cannot open the file; expected a readable URDF file");
  std::ostringstream text;
  text << in.rdbuf();
  return model_from_urdf_text(text.str(), path);
}

}  // namespace avar::kinematics
