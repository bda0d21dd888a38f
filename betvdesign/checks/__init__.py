"""Design verdicts: the rules, the fidelity ladder, adequacy and the check of a device."""
