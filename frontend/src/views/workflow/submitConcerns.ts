// What a reviewer would send a scene back for in its supports, said before it is submitted:
// objects without a supporter, and objects whose menus show a supporter the model suggests
// that nobody accepted (the stored one is what is submitted, not the suggestion).
import { plural, type SceneSession } from "../../state/sceneSession";
import { withoutSupporter } from "../../state/supportGraph";

type Supports = Pick<SceneSession, "objects" | "shown" | "displayed">;

const listed = (ids: string[], has: string) =>
  `${plural(ids.length, "object")} (${ids.join(", ")}) ${ids.length === 1 ? "has" : "have"} ${has}`;

/** One sentence per kind of unsettled support; none when every support is settled. */
export function unsettledSupports(session: Supports): string[] {
  const missing = withoutSupporter(session.objects, session.shown()).map((o) => o.id);
  const suggested = session.objects
    .filter((o) => session.displayed(o.id)?.suggested)
    .map((o) => o.id);
  return [
    ...(missing.length > 0 ? [listed(missing, "no supporter.")] : []),
    ...(suggested.length > 0
      ? [
          listed(
            suggested,
            "a supporter the model suggests and nobody accepted (dashed in the list): the " +
              "stored one is what is submitted.",
          ),
        ]
      : []),
  ];
}
