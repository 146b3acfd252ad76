// node web-view.js http://127.0.0.1:PORT/ SCREENSHOT.png: mpgc_record's built-in page in headless
// Chromium (Debian's /usr/bin/chromium, driven by playwright-core; no browser is downloaded) while
// the test publishes a scene of own ship and two confirmed or coasting targets (a third, tentative
// one must not be drawn), a head-on encounter, an OK plan and a charted island. Checks that the page
// loads from the server alone, draws the ships (the canvas's data-ships, the "Ships drawn" list, own
// ship's white pixels at the centre), the plan, the d_safety circles and the chart, shows the plan
// status and the encounter, and follows own ship as it moves.
// Exit 0 and "OK web view ..." when all holds; the screenshot is taken at the end.
const fs = require("fs");
const os = require("os");
const path = require("path");
const { chromium } = require("playwright-core");

const [url, shot] = process.argv.slice(2);
const ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--disable-background-networking",
  "--disable-component-update", "--disable-sync"];

(async () => {
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), "mpgc-chromium-"));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: "/usr/bin/chromium", headless: true, args: ARGS, viewport: { width: 1280, height: 800 },
  });
  const problems = [];
  try {
    const page = context.pages()[0] ?? (await context.newPage());
    const origin = new URL(url).origin;
    page.on("request", (r) => {
      if (!r.url().startsWith(origin) && !r.url().startsWith(origin.replace("http", "ws"))) problems.push(`request elsewhere: ${r.url()}`);
    });
    page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
    page.on("console", (m) => { if (m.type() === "error") problems.push(`console error: ${m.text()}`); });
    const resp = await page.goto(url);
    if (!resp.ok()) throw new Error(`GET ${url}: ${resp.status()}`);
    const canvas = page.locator("#view");
    // Own ship and the two targets drawn; the tentative track not.
    await page.waitForFunction(() => document.getElementById("view").dataset.ships === "3", null, { timeout: 30000 });
    // The plan (4 waypoints), the two targets' d_safety circles and the charted island.
    await page.waitForFunction(() => {
      const d = document.getElementById("view").dataset;
      return d.planPoints === "4" && d.circles === "2" && d.chartPolygons === "1";
    }, null, { timeout: 30000 }).catch(() => {});
    const data = await canvas.evaluate((c) => ({ ...c.dataset }));
    if (data.own !== "1" || data.targets !== "2") problems.push(`drawn: own ${data.own}, targets ${data.targets} (want 1 and 2)`);
    if (data.planPoints !== "4" || data.circles !== "2" || data.chartPolygons !== "1")
      problems.push(`drawn: plan points ${data.planPoints} (want 4), circles ${data.circles} (2), chart polygons ${data.chartPolygons} (1)`);
    await page.waitForFunction(() => document.querySelector("#encounters tbody tr") !== null, null, { timeout: 30000 });
    const plan = await page.locator("#plan-status").textContent();
    if (plan.trim() !== "OK") problems.push(`plan status shows "${plan}"`);
    const enc = await page.locator("#encounters tbody tr").first().evaluate((tr) => ({ situation: tr.dataset.situation, text: tr.textContent }));
    if (enc.situation !== "ENCOUNTER_HEAD_ON" || !/head-on/.test(enc.text) || !/give way/.test(enc.text) || !/mmsi_257000001/.test(enc.text))
      problems.push(`encounter row: ${JSON.stringify(enc)}`);
    const ships = await page.locator("#ships li").allTextContents();
    if (!ships.some((s) => s.startsWith("own ship")) || !ships.some((s) => s.startsWith("mmsi_257000001")) || !ships.some((s) => s.startsWith("track_2")))
      problems.push(`ships list: ${JSON.stringify(ships)}`);
    // Own ship is drawn white at the centre of the map.
    const white = await canvas.evaluate((c) => {
      const p = c.getContext("2d").getImageData(Math.floor(c.width / 2), Math.floor(c.height / 2 - 3 * devicePixelRatio), 1, 1).data;
      return p[0] > 240 && p[1] > 240 && p[2] > 240;
    });
    if (!white) problems.push("no own ship at the centre of the canvas");
    // It follows the run: own ship's position and the message count change.
    const own0 = await page.locator("#own").textContent();
    const n0 = Number(data.updates);
    await page.waitForFunction((before) => document.getElementById("own").textContent !== before, own0, { timeout: 15000 })
      .catch(() => problems.push(`own ship did not move on the page: "${own0}"`));
    const n1 = Number(await canvas.getAttribute("data-updates"));
    if (!(n1 > n0)) problems.push(`no messages received after the first draw (${n0} -> ${n1})`);
    const own1 = await page.locator("#own").textContent();
    await page.screenshot({ path: shot });
    if (problems.length > 0) throw new Error(problems.join("\n"));
    console.log(`OK web view: ${ships.length} ships drawn, plan ${plan.trim()}, ${enc.situation}; own ship "${own0}" -> "${own1}"; ${n1} messages`);
  } finally {
    await context.close();
    fs.rmSync(profile, { recursive: true, force: true });
  }
})().catch((e) => {
  console.error("FAIL:", e.message);
  process.exit(1);
});
