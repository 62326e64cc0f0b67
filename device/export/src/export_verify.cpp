#include "avar/device/export_verify.hpp"

#include <fstream>
#include <map>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "avar/device/tool_process.hpp"
#include "embedded_sources.hpp"

namespace avar::device {
namespace {

constexpr double kBuildTimeout = 600, kRunTimeout = 1800;

const std::map<std::string, EmulatedTarget>& emulations() {
  static const std::map<std::string, EmulatedTarget> all = {
      {"atmega328p", {"avr-g++", {"-mmcu=atmega328p"}, "simavr", {"-m", "atmega328p", "-f", "16000000"}, true}},
      {"atmega2560", {"avr-g++", {"-mmcu=atmega2560"}, "simavr", {"-m", "atmega2560", "-f", "16000000"}, true}},
      {"cortex-m0plus", {"arm-none-eabi-g++", {"-mcpu=cortex-m0plus", "-mthumb"}, "qemu-system-arm", {"-M", "microbit"}, false}},
      {"cortex-m3", {"arm-none-eabi-g++", {"-mcpu=cortex-m3", "-mthumb"}, "qemu-system-arm", {"-M", "lm3s6965evb"}, false}},
      {"cortex-m4", {"arm-none-eabi-g++", {"-mcpu=cortex-m4", "-mthumb"}, "qemu-system-arm", {"-M", "mps2-an386"}, false}},
  };
  return all;
}

const char* kInstall = " (scripts/install-deps.sh installs gcc-avr, avr-libc, simavr, gcc-arm-none-eabi and qemu-system-arm)";

/// `line` without terminal colour codes (ESC [ ... m) and surrounding blanks.
std::string plain(const std::string& line) {
  std::string out;
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (line[i] == '\x1b' && i + 1 < line.size() && line[i + 1] == '[') {
      const std::size_t m = line.find('m', i);
      if (m == std::string::npos) break;
      i = m;
      continue;
    }
    out += line[i];
  }
  const std::size_t first = out.find_first_not_of(" \r"), last = out.find_last_not_of(" \r");
  return first == std::string::npos ? std::string() : out.substr(first, last - first + 1);
}

/// Whether `line` is one the verification run prints: "show S SECOND HASH SAMPLES", "stream SECOND
/// HASH SAMPLES", "end S HASH SAMPLES", "samples N ticks T", or a refusal.
bool run_line(const std::string& line) {
  if (line == "figure refused" || line == "show refused") return true;
  std::stringstream in(line);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  const auto number = [](const std::string& w) { return !w.empty() && w.find_first_not_of("0123456789") == std::string::npos; };
  const auto hash = [](const std::string& w) {
    return w.size() == 8 && w.find_first_not_of("0123456789abcdef") == std::string::npos;
  };
  if (words.size() == 5 && words[0] == "show") return number(words[1]) && number(words[2]) && hash(words[3]) && number(words[4]);
  if (words.size() == 4 && (words[0] == "end" || words[0] == "stream"))
    return number(words[1]) && hash(words[2]) && number(words[3]);
  if (words.size() == 4 && words[0] == "samples") return number(words[1]) && words[2] == "ticks" && number(words[3]);
  return false;
}

/// The lines a run printed that the comparison reads: simavr colours each UART line and shows its
/// newline as a '.' before the line break.
std::vector<std::string> run_lines(const std::string& output, bool avr) {
  std::vector<std::string> lines;
  std::stringstream in(output);
  for (std::string raw; std::getline(in, raw);) {
    std::string line = plain(raw);
    if (avr) {
      if (line.empty() || line.back() != '.') continue;
      line.pop_back();
    }
    if (run_line(line)) lines.push_back(line);
  }
  return lines;
}

std::vector<std::string> sources_of(const std::filesystem::path& project_dir) {
  std::vector<std::string> sources;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(project_dir / "src")) {
    const auto& path = entry.path();
    if (path.extension() == ".cpp" && path.filename() != "avar_figure.cpp" && path.filename() != "avar_stream_figure.cpp")
      sources.push_back(path.string());  // not the Arduino glue
  }
  return sources;
}

void build(const std::vector<std::string>& command, const std::string& what) {
  const ToolRun run = run_tool(command, kBuildTimeout);
  if (run.status != 0)
    throw std::runtime_error("building the " + what + " failed" + (run.timed_out ? " (timed out)" : "") + ":\n" +
                             run.output.substr(0, 4000));
}

std::size_t size_field(const std::string& size_output, int column) {
  std::stringstream in(size_output);
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  std::stringstream fields(row);
  std::size_t value = 0;
  for (int i = 0; i <= column; ++i) fields >> value;
  return value;
}

}  // namespace

const EmulatedTarget* emulation_of(const DeviceTarget& target) {
  const auto found = emulations().find(std::string(target.name));
  return found == emulations().end() ? nullptr : &found->second;
}

ExportVerification verify_export(const Project& project, const std::filesystem::path& project_dir, std::ostream& progress) {
  const DeviceTarget& target = *project.target;
  const EmulatedTarget* emulated = emulation_of(target);
  if (target.host())
    throw std::runtime_error(
        "--verify compares a target's build with the host's; the host target is the host build: "
        "build it with its CMakeLists.txt and try it with --trace");
  if (emulated == nullptr)
    throw std::runtime_error("no emulator here runs the " + std::string(target.name) +
                             "; --verify runs atmega328p, atmega2560, cortex-m0plus, cortex-m3 and cortex-m4");
  const char* host_compiler = std::getenv("CXX");
  const std::string host_cxx = host_compiler != nullptr && *host_compiler != 0 ? host_compiler : "c++";
  for (const std::string& tool : {host_cxx, emulated->compiler, emulated->emulator})
    if (!find_program(tool)) throw std::runtime_error(tool + " is not installed" + kInstall);

  char pattern[] = "/tmp/avar-export-verify-XXXXXX";
  if (mkdtemp(pattern) == nullptr) throw std::runtime_error("cannot make a temporary directory for --verify");
  const std::filesystem::path work = pattern;
  struct Cleanup {
    std::filesystem::path dir;
    ~Cleanup() {
      std::error_code ignored;
      std::filesystem::remove_all(dir, ignored);
    }
  } cleanup{work};
  for (const EmbeddedSource& e : embedded_sources()) {
    const std::string path = e.path;
    if (path.rfind("verify/", 0) != 0) continue;
    std::ofstream(work / path.substr(7), std::ios::binary) << e.text;
  }
  const std::vector<std::string> sources = sources_of(project_dir);
  const char* main = project.stream ? "export_stream_verify_main.cpp" : "export_verify_main.cpp";
  const std::vector<std::string> common = {
      "-std=c++14",        "-ffreestanding", "-fno-exceptions", "-fno-rtti", "-I" + (project_dir / "src").string(),
      "-I" + work.string()};

  progress << "verify: building for the host (" << host_cxx << ")\n" << std::flush;
  std::vector<std::string> host = {host_cxx, "-O1", "-o", (work / "host").string()};
  host.insert(host.end(), common.begin(), common.end());
  host.insert(host.end(), sources.begin(), sources.end());
  host.push_back((work / main).string());
  host.push_back((work / "platform_host.cpp").string());
  build(host, "host build");

  progress << "verify: building for the " << target.name << " (" << emulated->compiler << ")\n" << std::flush;
  const std::string elf = (work / "target.elf").string();
  std::vector<std::string> cross = {emulated->compiler, "-Os", "-ffunction-sections", "-fdata-sections", "-Wl,--gc-sections"};
  cross.insert(cross.end(), emulated->flags.begin(), emulated->flags.end());
  cross.insert(cross.end(), common.begin(), common.end());
  if (!emulated->avr) cross.insert(cross.end(), {"-nostdlib", "-nostartfiles", "-T", (work / "cortex_m.ld").string()});
  cross.insert(cross.end(), sources.begin(), sources.end());
  cross.push_back((work / main).string());
  cross.push_back((work / (emulated->avr ? "platform_avr.cpp" : "platform_arm.cpp")).string());
  if (!emulated->avr) cross.push_back("-lgcc");
  cross.insert(cross.end(), {"-o", elf});
  build(cross, std::string(target.name) + " build");

  ExportVerification v;
  const ToolRun size = run_tool({emulated->avr ? "avr-size" : "arm-none-eabi-size", elf}, 60);
  if (size.status == 0) {
    v.flash_bytes = size_field(size.output, 0) + size_field(size.output, 1);
    v.ram_bytes = size_field(size.output, 1) + size_field(size.output, 2);
  }

  progress << "verify: running the host build\n" << std::flush;
  const ToolRun host_run = run_tool({(work / "host").string()}, kRunTimeout);
  const std::vector<std::string> reference = run_lines(host_run.output, false);
  if (host_run.status != 0 || reference.empty() || reference.back().rfind("samples ", 0) != 0)
    throw std::runtime_error("the host build's run failed:\n" + host_run.output.substr(0, 2000));

  std::vector<std::string> command = {emulated->emulator};
  if (emulated->avr) {
    command.insert(command.end(), emulated->emulator_args.begin(), emulated->emulator_args.end());
    command.push_back(elf);
  } else {
    command.insert(command.end(), emulated->emulator_args.begin(), emulated->emulator_args.end());
    command.insert(command.end(), {"-nographic", "-semihosting-config", "enable=on,target=native", "-kernel", elf});
  }
  v.emulator = emulated->emulator;
  progress << "verify: running the " << target.name << " build under " << emulated->emulator << "\n" << std::flush;
  const ToolRun device_run = run_tool(command, kRunTimeout);
  v.emulator_seconds = device_run.seconds;
  const std::vector<std::string> device = run_lines(device_run.output, emulated->avr);
  if (device.size() != reference.size())
    throw std::runtime_error("the " + std::string(target.name) + " run printed " + std::to_string(device.size()) +
                             " lines, the host's " + std::to_string(reference.size()) +
                             (device_run.timed_out ? " (timed out)" : "") + "; its output ends:\n" +
                             device_run.output.substr(device_run.output.size() > 2000 ? device_run.output.size() - 2000 : 0));
  for (std::size_t i = 0; i < reference.size(); ++i) {
    std::stringstream fields(reference[i]);
    std::string label;
    fields >> label;
    if (label == "samples") {
      std::string ticks_word;
      fields >> v.samples >> ticks_word >> v.ticks;
      if (device[i] != reference[i]) v.differing.push_back(reference[i] + " | " + device[i]);
      continue;
    }
    if (device[i] == reference[i]) continue;
    std::string a, b, hash;
    std::size_t samples = 0;
    std::stringstream again(reference[i]);
    if (label == "show") again >> a >> b >> b >> hash >> samples;
    else again >> a >> b >> hash >> samples;
    v.mismatches += samples;
    if (v.differing.size() < 10) v.differing.push_back(reference[i] + " | " + device[i]);
  }
  return v;
}

}  // namespace avar::device
