"""Which labs meet issue 31's full lab contract so far (README requirements mapped to criteria,
critical criteria, six mistakes, two correct variants). The other labs keep the older contract
(three mistakes) until their rubric is rewritten; the list only grows (docs/labs.md, Audit)."""

CONVERTED = {"bottle-packing", "bottle-reject", "bottling-recipes", "heater-pid", "level-4-20ma",
             "modbus-operator", "motor-start-stop", "pedestrian-crossing", "pump-station",
             "relay-thermostat", "scan-timing", "tank-two-position", "ventilation-fans",
             "washing-machine", "water-boiler"}
REQUIREMENTS_MAPPED = CONVERTED
