// What the page's scripts add to the browser's objects, for `tsc --checkJs` (ctest web_types):
// the player (player.js), the explorer's comparison (compare.js), the workbench (workbench.js) and the plots (plots.js).
interface CoverbenchPlayer {
  play(): void; pause(): void; seek(s: number): void; setSpeed(s: number): void; rescale(zoom: number): void;
  time(): number; playing(): boolean; speed(): number; duration(): number; frames(): number; lastFrame(): number; drawMs(): number; waypoints(): number; marked(): number;
}
interface CoverbenchZoom { set(zoom: number, cx?: number, cy?: number): void; zoom(): number; view: HTMLDivElement }
interface CoverbenchCompare {
  players: CoverbenchPlayer[]; play(): void; pause(): void; toggle(): void; seek(t: number): void; setSpeed(s: number): void;
  time(): number; speed(): number; duration(): number; playing(): boolean; times(): number[];
}
interface HTMLElement {
  coverbenchPlayer?: CoverbenchPlayer;
  coverbenchZoom?: CoverbenchZoom;
  coverbenchCompare?: CoverbenchCompare;
}
interface Window {
  coverbenchPlayback(raw: any): void;
  coverbenchAttachPlayer(figure: HTMLElement): void;
  coverbenchPlots: { show(exp: string, query: URLSearchParams, choice?: Record<string, string>, onChange?: (choice: Record<string, string>) => void): Promise<void>; drawn(): any; figure(): any; svgText(): string; pngBlob(): Promise<Blob> };
  Plot?: any;  // Observable Plot and d3, loaded by plots.js from /vendor/
  d3?: any;
  coverbenchCompareView: { open(viewer: HTMLElement, runs: any[], ctx: object): Promise<CoverbenchCompare | null> };
  coverbenchWorkbench: { setProblem(problem: object): void; plan(): Promise<void>; check(): Promise<void> };
}
