// All tools, by id, in the order the toolbar shows them.
import { ArrowTool } from './arrow-tool.js';
import { RotateTool } from './rotate-tool.js';
import { SelectTool } from './select-tool.js';
import { ShearTool } from './shear-tool.js';
import { StretchTool } from './stretch-tool.js';
import { ThickenTool } from './thicken-tool.js';
import { TwistTool } from './twist-tool.js';

// The tools flatten mode offers: painting the patch and placing directions.
export const FLATTEN_MODE_TOOLS = ['select', 'arrows'];

export function createTools(context) {
  const tools = [
    new SelectTool(context),
    new StretchTool(context),
    new ThickenTool(context),
    new ShearTool(context),
    new RotateTool(context),
    new TwistTool(context),
    new ArrowTool(context),
  ];
  return new Map(tools.map((tool) => [tool.id, tool]));
}
