"""The layout estimation and object detection networks of thesis Ch. 5 (LEN and ODN,
Total3DUnderstanding), smaller, on the COCO detector's backbone: docs/scene-net.md."""
