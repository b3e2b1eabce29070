// What the models page says about each kind of model.
import { percentText } from "../../dom";
import { SCORE_THRESHOLD } from "../../inference/detectorTensor";
import type { ModelKind } from "../../router";

export interface KindText {
  switchLabel: string;
  title: string;
  usedBy: string;
  empty: string;
  heldoutColumn: string;
  /** What the held-out figures count, one and many: labelled objects, confirmed boxes. */
  heldoutItems: [one: string, many: string];
  validationColumn: string;
  /** Why a model has no validation figure (the tooltip of its "—"). */
  noValidation: string;
  retrainHint: string;
  epochs: [label: string, placeholder: string];
  synthetic: [label: string, placeholder: string];
}

export const KIND_TEXT: Record<ModelKind, KindText> = {
  relation: {
    switchLabel: "Relation Network",
    title: "Relation Network models",
    usedBy:
      "It predicts, for each object of a photo, what holds it up (another object, the floor, " +
      "a wall or the ceiling) and how (from below or from behind): the support arrows. The " +
      "pipeline and the browser's suggestions use the active model; an admin can make any " +
      "model active again. The 3D networks (layout, boxes, meshes) ship with the app and are " +
      "trained with holiscene train-3d, not here.",
    empty: "No Relation Network model is registered yet: retrain to make one.",
    heldoutColumn: "Held-out accuracy",
    heldoutItems: ["labelled object", "labelled objects"],
    validationColumn: "Validation accuracy",
    noValidation: "No validation figure was recorded with this model.",
    retrainHint:
      "Trains a new Relation Network on the synthetic scenes and on every scene whose supports " +
      "a person set. About a fifth of their photos is held out (the same ones in every " +
      "retrain, each photo's scenes on one side; with few photos the share varies): the new " +
      "model becomes active only if it is more accurate on them than the active one, on 20 labelled objects or " +
      "more (exactly as accurate, or better on fewer: kept as a candidate, to make active by " +
      "hand). Every model is kept.",
    epochs: ["Epochs at most", "default (40)"],
    synthetic: ["Synthetic scenes", "default (1200)"],
  },
  detector: {
    switchLabel: "Object detector",
    title: "Object detector models",
    usedBy:
      "It finds the objects of a photo uploaded without boxes (each a box and an NYU-40 " +
      "class), in the pipeline and behind Detect objects. The pipeline uses the active " +
      "detector; an admin can make any detector active again.",
    empty: "No object detector is registered yet: retrain to make one.",
    heldoutColumn: "Held-out mAP@0.5 · recall",
    heldoutItems: ["confirmed box", "confirmed boxes"],
    validationColumn: "Validation mAP@0.5",
    noValidation:
      "Not trained here: a pretrained detector converted to ONNX, with no validation rooms of " +
      "this project. docs/benchmarks.md compares the detectors on real photos; a retrain " +
      "compares on your held-out scenes.",
    retrainHint:
      "Fine-tunes a new detector on synthetic rooms and on every scene whose boxes a person " +
      "confirmed: drawn, given with the photo, accepted suggestions, or all of a scene a " +
      "reviewer accepted. About a fifth of their photos is held out (the same ones in every " +
      "retrain, each photo's scenes on one side; with few photos the share varies): the new " +
      "detector becomes active only if it does better on them (mAP@0.5, then recall) on 20 confirmed boxes or " +
      "more; exactly as well, or better on fewer: kept as a candidate, to make active by " +
      "hand. Every detector is kept, and every other one is measured on the same held-out " +
      "scenes, to compare before making one active. mAP@0.5 ranks all its boxes down to 5%; recall counts " +
      `the confirmed boxes it finds with their class among the boxes it keeps (${percentText(SCORE_THRESHOLD)} ` +
      "or more, as the pipeline does), so a detector can have some mAP and no recall.",
    epochs: ["Epochs", "default (12)"],
    synthetic: ["Synthetic rooms", "default (300)"],
  },
};
