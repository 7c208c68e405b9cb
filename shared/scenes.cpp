// placeholder, replaced by the scene builders
