"""Which labs meet issue 31's full lab contract so far (README requirements mapped to criteria,
critical criteria, six mistakes, two correct variants). The other labs keep the older contract
(three mistakes) until their rubric is rewritten; the list only grows (docs/labs.md, Audit)."""

CONVERTED = {"drive-homing", "level-4-20ma", "modbus-operator", "motor-start-stop", "press-safety",
             "pump-station", "scan-timing", "tank-two-position", "ventilation-fans"}
REQUIREMENTS_MAPPED = CONVERTED | {"bottle-reject"}
