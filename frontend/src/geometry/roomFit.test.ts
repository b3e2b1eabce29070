// The TypeScript room fit against the shared vectors (shared_schema/vectors/room_fit.json):
// exact cases give back the truth, noisy ones the Python fit's output, errors the same message.
import { describe, expect, it } from "vitest";
import vectorsText from "../../../shared_schema/vectors/room_fit.json?raw";
import { BOX_CORNER_SIGNS } from "./boxes";
import type { Vec3 } from "./camera";
import { fitRoom, projectRoomCorners, type RoomFit, RoomFitError } from "./roomFit";

interface Expected {
  pitch_deg: number;
  roll_deg: number;
  room: { center: Vec3; size: Vec3; yaw_deg: number };
  corners_3d: Vec3[];
  rms_px: number;
}

interface VectorCase {
  name: string;
  kind: "exact" | "noisy" | "unseen_wall" | "error";
  input: {
    K: number[][];
    corners_2d: (number[] | null)[];
    camera_height: number;
    unseen_wall_distance: number | null;
  };
  expected: Expected | { error: string };
}

const vectors = JSON.parse(vectorsText) as { box_corner_signs: number[][]; cases: VectorCase[] };
const casesOf = (...kinds: VectorCase["kind"][]) =>
  vectors.cases.filter((c) => kinds.includes(c.kind));

const EXACT_TOLERANCE = 1e-5; // degrees and metres, against the truth
const PYTHON_TOLERANCE = 1e-4; // against the Python fit's output on noisy corners

function fitCase({ input }: VectorCase): RoomFit {
  return fitRoom(input.K, input.corners_2d, input.camera_height, {
    unseenWallDistance: input.unseen_wall_distance,
  });
}

function expectFitToMatch(fit: RoomFit, expected: Expected, tolerance: number): void {
  const largestDifference = (got: readonly number[], want: readonly number[]) =>
    Math.max(...got.map((x, i) => Math.abs(x - (want[i] ?? Number.NaN))));
  const differences = {
    pitch: Math.abs(fit.pitchDeg - expected.pitch_deg),
    roll: Math.abs(fit.rollDeg - expected.roll_deg),
    yaw: Math.abs(fit.room.yawDeg - expected.room.yaw_deg),
    center: largestDifference(fit.room.center, expected.room.center),
    size: largestDifference(fit.room.size, expected.room.size),
    corners: largestDifference(fit.corners3d.flat(), expected.corners_3d.flat()),
    rms: Math.abs(fit.rmsPx - expected.rms_px),
  };
  for (const [field, difference] of Object.entries(differences)) {
    expect(difference, field).toBeLessThanOrEqual(tolerance);
  }
  expect(fit.converged).toBe(true);
}

describe("fitRoom on the shared vectors", () => {
  it("uses the contract's corner order", () => {
    expect(BOX_CORNER_SIGNS).toEqual(vectors.box_corner_signs);
  });

  it.each(casesOf("exact", "unseen_wall"))("$name: gives back the truth", (testCase) => {
    expectFitToMatch(fitCase(testCase), testCase.expected as Expected, EXACT_TOLERANCE);
  });

  it.each(casesOf("noisy"))("$name: agrees with the Python fit", (testCase) => {
    expectFitToMatch(fitCase(testCase), testCase.expected as Expected, PYTHON_TOLERANCE);
  });

  it.each(casesOf("error"))("$name: refuses the input", (testCase) => {
    const { error } = testCase.expected as { error: string };
    expect(() => fitCase(testCase)).toThrow(RoomFitError);
    expect(() => fitCase(testCase)).toThrow(error);
  });

  it.each(casesOf("exact"))("$name: projects back onto the corners given", (testCase) => {
    const fit = fitCase(testCase);
    const projected = projectRoomCorners(
      testCase.input.K,
      fit.pitchDeg,
      fit.rollDeg,
      fit.corners3d,
    );
    projected.forEach((point, i) => {
      const given = testCase.input.corners_2d[i] ?? null;
      expect(point === null).toBe(given === null);
      if (point !== null && given !== null) {
        const scale = 1 + Math.hypot(given[0] ?? 0, given[1] ?? 0);
        expect(
          Math.hypot(point[0] - (given[0] ?? 0), point[1] - (given[1] ?? 0)) / scale,
        ).toBeLessThan(1e-9);
      }
    });
  });

  it.each([
    [
      {
        K: [
          [500, 0, 320],
          [0, 500],
          [0, 0, 1],
        ],
      },
      "K must be a 3x3 matrix",
    ],
    [
      {
        K: [
          [Number.NaN, 0, 320],
          [0, 500, 240],
          [0, 0, 1],
        ],
      },
      "K must be a 3x3 matrix",
    ],
    [{ camera_height: -1.4 }, "camera_height must be a positive"],
    [{ unseen_wall_distance: -0.5 }, "unseen_wall_distance must be a positive"],
  ])("refuses bad arguments as the Python fit does: %j", (change, message) => {
    const [testCase] = casesOf("exact") as [VectorCase];
    const input = { ...testCase.input, ...change };
    expect(() => fitCase({ ...testCase, input })).toThrow(message);
  });
});

describe("fitRoom's start", () => {
  // One floor corner (1) in a 730 x 530 photo, the others extrapolated far outside it
  // (backend tests/geometry/test_room_fit.py has the same room).
  const K = [
    [632.2, 0, 365],
    [0, 632.2, 265],
    [0, 0, 1],
  ];
  const corners: ([number, number] | null)[] = [
    [-1179.94, 1080.88],
    [219.33, 223.45],
    [962.6, 295.86],
    null,
    [-22135.56, -6569.82],
    [157.64, -172.67],
    [1205.78, -352.11],
    null,
  ];

  it("is the room shown when a drag tips the corners' own start behind the camera", () => {
    const shown = fitRoom(K, corners, 1.77);
    expect(shown.rmsPx).toBeLessThan(1);
    const dragged = [...corners];
    dragged[1] = [199.33, 253.45]; // 20 px left, 30 px down
    expect(() => fitRoom(K, dragged, 1.77)).toThrow(/initial guess puts a known corner behind/);
    const fit = fitRoom(K, dragged, 1.77, { start: shown });
    expect(fit.converged).toBe(true);
    expect(fit.rmsPx).toBeLessThan(20);
    for (const side of fit.room.size) expect(side).toBeGreaterThan(0.5);
    // Corners that give their own start ignore it.
    const same = fitRoom(K, corners, 1.77, { start: shown });
    expect(same.trials).toBe(shown.trials);
  });
});
