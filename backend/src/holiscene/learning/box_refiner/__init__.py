"""A learned refinement of the single-photo 3D boxes (thesis Ch. 5, the object detection
network's role): per object, how far along its ray and how large its box is, given what the
geometric pipeline measured, read with the object relation module over the other objects."""
