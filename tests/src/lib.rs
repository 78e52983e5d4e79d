//! Shared test helpers: a strict mock target and independent reference rasterizers.
