// The simulator's settings: the tissue's material (Young's modulus,
// Poisson's ratio, density), the wrinkles (4.4: frequency theta^d, scale s,
// magnitude bound m^up, window e - s) and the cut surface (5.3.4: rows,
// fragments removed whole). Apply validates them as a scenario file is
// (applyScenarioSettings: the message names the setting's key) and hands
// the changed scenario to the window, which applies it to the running
// scene (material, wrinkles) or, for the cut surface of a tissue being
// cut, starts it again; on an error the panel says why and the running
// scenario goes on.
#ifndef SettingsPanel_h
#define SettingsPanel_h

#include "Scenario.h"

#include <QWidget>

#include <functional>
#include <map>
#include <string>

class QLabel;
class QLineEdit;

namespace thintissue
{

class SettingsPanel : public QWidget
{
  Q_OBJECT
public:
  /// `start` applies a changed scenario (live or by starting it again);
  /// false if it could not (it said why).
  using Starter = std::function<bool(const ScenarioDescription&)>;
  SettingsPanel(Starter start, QWidget* parent = nullptr);

  /// Shows the settings of the running scenario.
  void show(const ScenarioDescription& scenario);
  /// The field for a key (e.g. "tissue.material.youngModulus"), for tests.
  QLineEdit* field(const std::string& key) const;
  /// Validates the fields and starts the scenario with them; false (and the
  /// reason shown) when a value is refused or the scenario did not start.
  bool apply();
  /// The last refusal ("" after a good apply).
  QString error() const;

private:
  /// The fields as a JSON object of scenario keys; throws naming the
  /// setting when a field is not a number.
  std::string settingsJson() const;

  Starter Start;
  ScenarioDescription Running;
  std::map<std::string, QLineEdit*> Fields;
  QLabel* Message = nullptr;
};

} // namespace thintissue

#endif
