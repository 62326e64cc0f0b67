// A message to the studio, as its page or any program on the network sends it: the parser must
// take it or throw a ProtocolError, nothing else; an edit it carries, applied to the hello-head
// show, must apply or throw an EditError, and leave a show whose curves sample finite values.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "avar/config/show_file.hpp"
#include "avar/edit/show_document.hpp"
#include "avar/studio/protocol.hpp"
#include "fuzz_bytes.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const avar::playback::Show show = avar::config::load_show_file(AVAR_FUZZ_EXAMPLES_DIR "/shows/hello-head.yaml");
  static const std::vector<std::string> channels = [] {
    std::vector<std::string> names;
    for (const avar::playback::Track& t : show.tracks) names.push_back(t.channel);
    return names;
  }();
  avar::studio::ClientMessage message;
  try {
    message = avar::studio::parse_client_message(avar::fuzz::as_text(data, size), channels);
  } catch (const avar::studio::ProtocolError&) {
    return 0;
  }
  const auto* edit = std::get_if<avar::studio::Edit>(&message);
  if (!edit) return 0;
  avar::edit::ShowDocument doc(show);
  try {
    doc.apply(edit->edits);
    if (edit->continues) doc.continue_last(edit->edits);
  } catch (const avar::edit::EditError&) {
    return 0;
  }
  for (const avar::playback::Track& t : doc.show().tracks)
    for (double s = -1; s < 14; s += 0.25)
      if (!std::isfinite(t.curve.evaluate(s))) __builtin_trap();
  doc.undo();
  return 0;
}
