"""What the server and the command line run on top of the store: the workbench (scenes, jobs,
models), one photo through the pipeline (reconstruction) and the retraining jobs of the
Relation Network and the object detector."""
