"""Which labs meet issue 31's full lab contract (README requirements mapped to criteria,
critical criteria, six mistakes, two correct variants): all seventeen since issue 31's second
round (docs/labs.md, Audit); a new lab joins the list when it meets the contract."""

CONVERTED = {"bottle-packing", "bottle-reject", "bottling-recipes", "drive-homing", "heater-pid",
             "level-4-20ma", "modbus-operator", "motor-start-stop", "pedestrian-crossing",
             "press-safety", "pump-station", "relay-thermostat", "scan-timing",
             "tank-two-position", "ventilation-fans", "washing-machine", "water-boiler"}
REQUIREMENTS_MAPPED = CONVERTED
