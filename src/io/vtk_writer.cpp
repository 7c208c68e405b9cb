// placeholder, replaced by the VTK writer
