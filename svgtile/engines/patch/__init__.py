"""The patch engine (AlMeraj, Kaplan & Asente 2013)."""
