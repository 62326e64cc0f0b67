#include "avar/mocap/bvh_reader.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <iterator>
#include <numbers>
#include <stdexcept>
#include <unordered_map>

#include "bvh_lexer.hpp"

namespace avar::mocap {
namespace {

using bvh::Lexer;
using bvh::Token;

/// Deeper nesting than this is refused (it would only come from a broken or hostile file).
constexpr int kBvhMaxDepth = 1000;

enum class BvhChannel : std::uint8_t { x_position, y_position, z_position, x_rotation, y_rotation, z_rotation };
constexpr std::array<const char*, 6> kBvhChannelNames{"Xposition", "Yposition", "Zposition",
                                                      "Xrotation", "Yrotation", "Zrotation"};

bool bvh_keyword(std::string_view word, std::string_view keyword) {
  return word.size() == keyword.size() && std::equal(word.begin(), word.end(), keyword.begin(), [](char a, char b) {
           return (a >= 'A' && a <= 'Z' ? a - 'A' + 'a' : a) == (b >= 'A' && b <= 'Z' ? b - 'A' + 'a' : b);
         });
}

std::optional<BvhChannel> bvh_channel(std::string_view word) {
  for (std::size_t c = 0; c < kBvhChannelNames.size(); ++c)
    if (bvh_keyword(word, kBvhChannelNames[c])) return static_cast<BvhChannel>(c);
  return std::nullopt;
}

/// The hierarchy in pre-order (the order of the values in every MOTION row).
struct BvhHierarchy {
  std::vector<Joint> joints;
  std::vector<std::vector<BvhChannel>> channels;
  std::size_t value_count = 0;
};

class BvhHierarchyParser {
 public:
  BvhHierarchyParser(Lexer& lexer, BvhHierarchy& out) : lexer_(lexer), out_(out) {}

  void joint(const Token& name, std::ptrdiff_t parent, int depth) {
    if (depth > kBvhMaxDepth) lexer_.fail(name, "joints nest deeper than " + std::to_string(kBvhMaxDepth) + " levels");
    if (name.end()) lexer_.fail(name, "expected a joint name after ROOT or JOINT, found the end of the line");
    const std::size_t index = add(name, parent, false);
    const Token open = expect_open(name.text);
    bool have_offset = false, have_channels = false;
    for (;;) {
      const Token token = lexer_.next();
      if (token.end()) {
        lexer_.fail(token, "expected '}' closing joint '" + std::string(name.text) + "' (opened at line " +
                               std::to_string(open.line) + "), found the end of the file");
      }
      if (token.text == "}") {
        if (!have_offset) lexer_.fail(token, "expected an OFFSET in joint '" + std::string(name.text) + "' before its '}'");
        return;
      }
      if (bvh_keyword(token.text, "OFFSET")) {
        if (have_offset) lexer_.fail(token, "a second OFFSET in joint '" + std::string(name.text) + "'; expected one");
        out_.joints[index].rest_translation = offset();
        have_offset = true;
      } else if (bvh_keyword(token.text, "CHANNELS")) {
        if (have_channels) lexer_.fail(token, "a second CHANNELS in joint '" + std::string(name.text) + "'; expected one");
        out_.channels[index] = channels();
        out_.value_count += out_.channels[index].size();
        have_channels = true;
      } else if (bvh_keyword(token.text, "JOINT")) {
        joint(lexer_.rest_of_line(), static_cast<std::ptrdiff_t>(index), depth + 1);
      } else if (bvh_keyword(token.text, "End")) {
        end_site(index);
      } else if (bvh_keyword(token.text, "ROOT")) {
        lexer_.fail(token, "a ROOT inside joint '" + std::string(name.text) + "'; expected JOINT (or '}' first)");
      } else {
        lexer_.fail(token, "expected OFFSET, CHANNELS, JOINT, End Site or '}' in joint '" + std::string(name.text) + "', found " +
                               Lexer::describe(token));
      }
    }
  }

 private:
  std::size_t add(const Token& name, std::ptrdiff_t parent, bool end_site) {
    std::string text(name.text);
    const auto [seen, fresh] = names_.emplace(text, name.line);
    if (!fresh) {
      lexer_.fail(name, "joint name '" + text + "' is used twice (first at line " + std::to_string(seen->second) +
                            "); expected unique names" + (end_site ? " (an End Site is named <parent>_end)" : ""));
    }
    Joint joint;
    joint.name = std::move(text);
    joint.parent = parent;
    joint.end_site = end_site;
    out_.joints.push_back(std::move(joint));
    out_.channels.emplace_back();
    return out_.joints.size() - 1;
  }

  Token expect_open(std::string_view owner) {
    const Token open = lexer_.next();
    if (open.text != "{") lexer_.fail(open, "expected '{' opening '" + std::string(owner) + "', found " + Lexer::describe(open));
    return open;
  }

  Eigen::Vector3d offset() {
    Eigen::Vector3d v;
    static constexpr std::array<const char*, 3> what{"OFFSET's x", "OFFSET's y", "OFFSET's z"};
    for (int k = 0; k < 3; ++k) v[k] = lexer_.number(lexer_.next_on_line(), what[static_cast<std::size_t>(k)]);
    return v;
  }

  std::vector<BvhChannel> channels() {
    const Token count_token = lexer_.next_on_line();
    const double count = lexer_.number(count_token, "the CHANNELS count");
    if (count != std::floor(count) || count < 0 || count > 6)
      lexer_.fail(count_token, "expected a CHANNELS count from 0 to 6, found " + Lexer::describe(count_token));
    std::vector<BvhChannel> list;
    for (int i = 0; i < static_cast<int>(count); ++i) {
      const Token name = lexer_.next_on_line();
      const auto channel = bvh_channel(name.text);
      if (!channel) {
        lexer_.fail(name, "expected channel " + std::to_string(i + 1) + " of " + std::string(count_token.text) +
                              " (Xposition, Yposition, Zposition, Xrotation, Yrotation or Zrotation), found " +
                              Lexer::describe(name, true));
      }
      if (std::find(list.begin(), list.end(), *channel) != list.end())
        lexer_.fail(name, "channel " + std::string(name.text) + " is listed twice; expected each at most once");
      list.push_back(*channel);
    }
    return list;
  }

  void end_site(std::size_t parent) {
    const Token site = lexer_.next_on_line();
    if (!bvh_keyword(site.text, "Site")) lexer_.fail(site, "expected 'Site' after 'End', found " + Lexer::describe(site, true));
    const std::string name = out_.joints[parent].name + "_end";
    const std::size_t index = add(Token{name, site.line, site.column}, static_cast<std::ptrdiff_t>(parent), true);
    const Token open = expect_open("End Site");
    const Token keyword = lexer_.next();
    if (!bvh_keyword(keyword.text, "OFFSET"))
      lexer_.fail(keyword,
                  "expected OFFSET in the End Site of '" + out_.joints[parent].name + "', found " + Lexer::describe(keyword));
    out_.joints[index].rest_translation = offset();
    const Token close = lexer_.next();
    if (close.text != "}") {
      lexer_.fail(close, "expected '}' closing the End Site opened at line " + std::to_string(open.line) + ", found " +
                             Lexer::describe(close));
    }
  }

  Lexer& lexer_;
  BvhHierarchy& out_;
  std::unordered_map<std::string, int> names_;
};

void bvh_expect_keyword(Lexer& lexer, const Token& token, std::string_view keyword, const std::string& context) {
  if (!bvh_keyword(token.text, keyword))
    lexer.fail(token, "expected '" + std::string(keyword) + "'" + context + ", found " + Lexer::describe(token));
}

BvhHierarchy bvh_read_hierarchy(Lexer& lexer) {
  bvh_expect_keyword(lexer, lexer.next(), "HIERARCHY", " at the start of a BVH file");
  const Token root = lexer.next();
  bvh_expect_keyword(lexer, root, "ROOT", " after HIERARCHY");
  BvhHierarchy hierarchy;
  BvhHierarchyParser(lexer, hierarchy).joint(lexer.rest_of_line(), kNoParent, 0);
  if (hierarchy.value_count == 0) lexer.fail(root, "the hierarchy has no CHANNELS; expected at least one channel to animate");
  return hierarchy;
}

/// The `Frames: N` count (at least 1).
std::size_t bvh_read_frame_count(Lexer& lexer) {
  const Token motion = lexer.next();
  if (bvh_keyword(motion.text, "ROOT")) lexer.fail(motion, "a second ROOT; expected one skeleton per file, then MOTION");
  bvh_expect_keyword(lexer, motion, "MOTION", " after the hierarchy");
  bvh_expect_keyword(lexer, lexer.next(), "Frames:", " after MOTION");
  const Token count = lexer.next_on_line();
  std::size_t frames = 0;
  const auto [ptr, ec] = std::from_chars(count.text.data(), count.text.data() + count.text.size(), frames);
  if (count.end() || ec != std::errc() || ptr != count.text.data() + count.text.size() || frames == 0)
    lexer.fail(count, "expected a frame count of at least 1 after 'Frames:', found " + Lexer::describe(count, true));
  return frames;
}

double bvh_read_frame_time(Lexer& lexer) {
  bvh_expect_keyword(lexer, lexer.next(), "Frame", " (of 'Frame Time:') after the frame count");
  bvh_expect_keyword(lexer, lexer.next_on_line(), "Time:", " after 'Frame'");
  const Token value = lexer.next_on_line();
  const double seconds = lexer.number(value, "the frame time in seconds");
  if (!(seconds > 0)) lexer.fail(value, "expected a frame time of more than 0 s, found " + Lexer::describe(value));
  const Token rest = lexer.next_on_line();
  if (!rest.end()) lexer.fail(rest, "expected the end of the line after the frame time, found " + Lexer::describe(rest));
  return seconds;
}

/// The local pose of one MOTION row (`values` in hierarchy order).
void bvh_pose_from_row(const BvhHierarchy& hierarchy, const std::vector<double>& values, Pose& pose) {
  const std::size_t count = hierarchy.joints.size();
  pose.translation.resize(count);
  pose.rotation.resize(count);
  pose.scale.assign(count, Eigen::Vector3d::Ones());
  std::size_t next = 0;
  for (std::size_t j = 0; j < count; ++j) {
    Eigen::Vector3d translation = hierarchy.joints[j].rest_translation;
    Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
    for (const BvhChannel channel : hierarchy.channels[j]) {
      const double value = values[next++];
      const auto axis = static_cast<Eigen::Index>(static_cast<int>(channel) % 3);
      if (channel <= BvhChannel::z_position) {
        translation[axis] += value;
      } else {
        // The first listed rotation is outermost: post-multiplying applies later channels inside.
        rotation =
            rotation * Eigen::Quaterniond(Eigen::AngleAxisd(value * std::numbers::pi / 180.0, Eigen::Vector3d::Unit(axis)));
      }
    }
    pose.translation[j] = translation;
    pose.rotation[j] = rotation.normalized();
  }
}

void bvh_read_frames(Lexer& lexer, const BvhHierarchy& hierarchy, std::size_t declared, std::size_t text_size,
                     SkeletonAnimation& animation) {
  std::vector<double> values(hierarchy.value_count);
  // Every row holds value_count numbers of at least two characters each (digit and separator):
  // a huge Frames: in a small file reserves no more than the file can hold.
  animation.frames.reserve(std::min(declared, text_size / (2 * values.size()) + 1));
  while (lexer.next_line()) {
    Token token = lexer.next_on_line();
    if (token.end()) continue;  // a blank line
    if (animation.frames.size() == declared) {
      lexer.fail(token, "more rows than the " + std::to_string(declared) + " frames 'Frames:' declares");
    }
    std::size_t count = 0;
    for (; !token.end(); token = lexer.next_on_line()) {
      if (count == values.size()) {
        lexer.fail(token, "frame " + std::to_string(animation.frames.size()) + " holds more than " +
                              std::to_string(values.size()) + " values; expected one per channel (" +
                              std::to_string(values.size()) + ")");
      }
      values[count++] = lexer.number(token, "a channel value");
    }
    if (count != values.size()) {
      lexer.fail(token, "frame " + std::to_string(animation.frames.size()) + " holds " + std::to_string(count) +
                            " values; expected one per channel (" + std::to_string(values.size()) + ")");
    }
    animation.frames.emplace_back();
    bvh_pose_from_row(hierarchy, values, animation.frames.back());
  }
  if (animation.frames.size() != declared) {
    lexer.fail(lexer.here(), "the file ends after " + std::to_string(animation.frames.size()) + " rows; expected " +
                                 std::to_string(declared) + " frames as 'Frames:' declares");
  }
}

std::string bvh_read_whole_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path, 0, 0}, std::string("cannot read the file: ") + std::strerror(errno));
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InputError({path, 0, 0}, "cannot read the file to its end");
  return text;
}

}  // namespace

SkeletonAnimation parse_bvh(std::string_view text, const std::string& source) {
  Lexer lexer(text, source);
  BvhHierarchy hierarchy = bvh_read_hierarchy(lexer);
  const std::size_t declared = bvh_read_frame_count(lexer);
  SkeletonAnimation animation;
  animation.source = source;
  animation.frame_time = bvh_read_frame_time(lexer);
  bvh_read_frames(lexer, hierarchy, declared, text.size(), animation);
  animation.joints = std::move(hierarchy.joints);
  animation.channels.reserve(hierarchy.channels.size());
  for (const auto& list : hierarchy.channels) {
    auto& names = animation.channels.emplace_back();
    for (const BvhChannel channel : list) names.emplace_back(kBvhChannelNames[static_cast<std::size_t>(channel)]);
  }
  align_hemispheres(animation);
  try {
    validate(animation);
  } catch (const std::invalid_argument& e) {
    throw InputError({source, 0, 0}, e.what());
  }
  return animation;
}

SkeletonAnimation load_bvh(const std::string& path) { return parse_bvh(bvh_read_whole_file(path), path); }

}  // namespace avar::mocap
