"""``ringcontact bearing``: a ring-pair file to a verified contact law (FEM references, calibration,
accuracy report, law file). Modules: :mod:`~reports.bearing.names` (file names, the error bound),
:mod:`~reports.bearing.pipeline` (the stages), :mod:`~reports.bearing.report` (the accuracy report)."""
