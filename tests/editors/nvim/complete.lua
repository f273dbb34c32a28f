-- Headless Neovim completes as a user does: `mcc lsp` attached with Neovim's built-in client,
-- the cursor put at the end of line $MCC_LINE, then the keys `A` (append) and CTRL-X CTRL-O
-- (omni completion, 'omnifunc' set to the LSP client's, as Neovim's documentation suggests). The
-- popup's items are read back (complete_info: each item's word, its label and the textEdit range
-- the server sent), the item labelled $MCC_PICK is chosen with CTRL-N and accepted with CTRL-Y,
-- and the line as it is then is written with the items to the JSON file $MCC_NVIM_OUT.
-- Works with Neovim 0.7 (Debian's package) and later.
local out = os.getenv("MCC_NVIM_OUT")
local python = os.getenv("MCC_PYTHON")
local lnum = tonumber(os.getenv("MCC_LINE"))
local pick = os.getenv("MCC_PICK")
local result = { items = {}, line = nil, error = nil }

local function finish()
  local file = io.open(out, "w")
  file:write(vim.fn.json_encode(result))
  file:close()
  vim.cmd("qa!")
end

local function fail(message)
  result.error = message
  finish()
end

local function keys(text)
  vim.api.nvim_feedkeys(vim.api.nvim_replace_termcodes(text, true, false, true), "n", false)
end

local bufnr = vim.api.nvim_get_current_buf()

local function poll(count)
  local info = vim.fn.complete_info({ "items" })
  if #info.items == 0 then
    if count > 600 then
      return fail("no completion items within 60 s (line: " .. vim.api.nvim_get_current_line() .. ")")
    end
    return vim.defer_fn(function() poll(count + 1) end, 100)
  end
  local chosen = nil
  for index, item in ipairs(info.items) do
    local lsp = type(item.user_data) == "table" and item.user_data.nvim and item.user_data.nvim.lsp
    local completion = lsp and lsp.completion_item or {}
    local range = completion.textEdit and completion.textEdit.range or vim.NIL
    table.insert(result.items, { word = item.word, abbr = item.abbr, range = range })
    if item.abbr == pick and chosen == nil then
      chosen = index
    end
  end
  if chosen == nil then
    keys("<C-e><Esc>")
    return vim.defer_fn(function() fail("no item labelled " .. pick) end, 200)
  end
  -- the first item is selected ('completeopt' noinsert): CTRL-N down to the chosen one, CTRL-Y
  keys(string.rep("<C-n>", chosen - 1) .. "<C-y><Esc>")
  vim.defer_fn(function()
    result.line = vim.api.nvim_buf_get_lines(bufnr, lnum - 1, lnum, false)[1]
    finish()
  end, 300)
end

local ok, err = pcall(function()
  local client_id = vim.lsp.start_client({ name = "mcc", cmd = { python, "-m", "mcc", "lsp" },
                                           root_dir = vim.fn.getcwd() })
  assert(client_id, "the mcc language server did not start")
  vim.lsp.buf_attach_client(bufnr, client_id)
  -- a request sent before the server has answered `initialize` is refused at once ("not
  -- supported"), and buf_request_sync then waits out its whole timeout: wait for the handshake
  local started = vim.wait(60000, function()
    local client = vim.lsp.get_client_by_id(client_id)
    return client ~= nil and client.initialized == true
  end, 20)
  assert(started, "the mcc language server did not answer initialize within 60 s")
  -- completion answers from the server's latest finished analysis: wait until it has one
  local params = { uri = vim.uri_from_bufnr(bufnr) }
  local ready = false
  for _ = 1, 240 do
    for _, response in pairs(vim.lsp.buf_request_sync(bufnr, "mcc/status", params, 5000) or {}) do
      if response.result and response.result.complete then
        ready = true
      end
    end
    if ready then
      break
    end
    vim.wait(250)
  end
  assert(ready, "the server did not finish analysing the file within 60 s")
  vim.bo[bufnr].omnifunc = "v:lua.vim.lsp.omnifunc"
  vim.o.completeopt = "menuone,noinsert"
  vim.api.nvim_win_set_cursor(0, { lnum, 0 })
  keys("A<C-x><C-o>")
end)
if not ok then
  fail(tostring(err))
else
  vim.defer_fn(function() poll(0) end, 100)
end
