"""Analysis: what synthesis must reproduce (almeraj2013 §3.1–3.5)."""
